// A quantized-mesh tile's triangles sampled on a block's grid: block_size²
// heights, corner-registered (the tile's edges on the first and last rows
// and columns), row 0 at the north. Grid point (i, j) lies at
// u = i / (B - 1) * 32767 and, by default, v = (1 - j / (B - 1)) * 32767
// (a geodetic tile: rows evenly spaced in latitude, as v is); a web
// mercator tile's rows are evenly spaced in mercator y while its v is linear
// in latitude, so the caller gives each row's v (mercator_row_v). The point
// takes the height of the triangle holding it, interpolated barycentrically.
//
// Containment and the weights come from exact integer orientation tests on
// the quantized coordinates (scaled so that every grid point is an integer
// too; rows given as v are rounded to 1/(F (B - 1)) of a unit, F >= 7), so a
// point on an edge belongs to that edge in every triangle and every tile
// sharing it, and its height is the linear interpolation between the edge's
// two vertices computed one way (endpoints in a fixed order): neighbouring
// tiles whose edge vertices agree give identical edge samples. Zero-area
// triangles are skipped; a point in no triangle is NaN. Pure arithmetic on a
// decoded QuantizedMesh (quantized_mesh_decode.hpp); used by
// quantized_mesh_reader.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "data/quantized_mesh_decode.hpp"

namespace globe::viewer {

// block_size in 2..4097; row_v empty (evenly spaced rows) or block_size
// values, north row first, each in 0..32767 (std::invalid_argument
// otherwise). The mesh must be as decode_quantized_mesh returns it
// (indices below the vertex count).
std::vector<float> mesh_grid(const QuantizedMesh& mesh, int block_size,
                             std::span<const double> row_v = {});

// The v of each row of a web mercator tile's block (z, y: XYZ row from the
// north), north row first: 32767 and 0 on the tile's edges, between them
// the latitude of the row's mercator y, linear between the tile's south and
// north latitudes as quantized-mesh's v is.
std::vector<double> mercator_row_v(int z, uint32_t y, int block_size);

}  // namespace globe::viewer
