// --export-mesh: the triangles drawn for a view as a binary PLY, vertices
// welded (a vertex drawn by several patches is one vertex). Coordinates are
// the tiling CRS (x, y) and the height in metres (z), doubles. Header
// comments record what a checker needs to recompute projected errors:
//   comment globe crs_per_key, metres_per_crs X Y, height_scale S
//   comment globe eye_crs X Y Z_METRES, pixels_per_radian K, max_error_px T
#pragma once

#include <string>
#include <vector>

#include "camera/camera.hpp"
#include "camera/world_frame.hpp"

namespace globe::viewer {

// triangles: 9 floats per triangle, world metres relative to view.origin (as
// captured from the GPU). Throws OutputError.
void write_mesh_ply(const std::string& path, const std::vector<float>& triangles, const View& view,
                    const WorldFrame& frame, double exaggeration, double max_error_px);

}  // namespace globe::viewer
