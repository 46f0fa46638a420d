// --export-mesh: the triangles drawn for a view as a binary PLY, vertices
// welded (a vertex drawn by several patches is one vertex: same key point and
// height). Coordinates, doubles, computed from each vertex's key point:
//   flat frame: the tiling CRS (x, y) and the height in metres (z);
//   globe: geocentric WGS84 (ECEF) metres, heights along the normal.
// Header comments say which, and record what a checker needs to recompute
// projected errors:
//   comment globe frame flat|geocentric, crs, metres_per_crs X Y, height_scale S
//   comment globe eye X Y Z (the same coordinates), pixels_per_radian K,
//   max_error_px T
#pragma once

#include <string>
#include <vector>

#include "camera/camera.hpp"
#include "camera/world_frame.hpp"
#include "render/terrain_renderer.hpp"

namespace globe::viewer {

// triangles: 3 captured vertices per triangle. Throws OutputError.
void write_mesh_ply(const std::string& path, const std::vector<CapturedVertex>& triangles,
                    const View& view, const WorldFrame& frame, double exaggeration,
                    double max_error_px);

}  // namespace globe::viewer
