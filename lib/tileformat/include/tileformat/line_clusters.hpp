// The cluster-grid rule of line-cluster tiles (docs/tileformat.md §7.3):
// a segment is listed in a cell iff the distance from the segment to the
// closed cell rectangle is at most `reach`. Writers build grids with it and
// validators recompute it, so both sides apply the very same test.
#pragma once

#include <cstdint>
#include <functional>

#include "tileformat/line_tile.hpp"

namespace tileformat {

// Liang-Barsky: the part of segment (ax, ay)-(bx, by) inside the closed
// rectangle [x0, x1] x [y0, y1] is t0..t1 (0 <= t0 <= t1 <= 1) along it;
// false if the segment misses the rectangle.
bool clip_parameters(double ax, double ay, double bx, double by, double x0, double y0, double x1,
                     double y1, double& t0, double& t1);

// Euclidean distance between segment ab and the closed rectangle
// [x0, x1] x [y0, y1] (0 if they intersect).
double segment_rect_distance(LineVertex a, LineVertex b, double x0, double y0, double x1,
                             double y1);
// Distance between point p and segment ab.
double point_segment_distance(double px, double py, LineVertex a, LineVertex b);

// Calls fn(cell) for every cell of `tile`'s grid the footprint of ab touches,
// in ascending cell order.
void for_each_cell_in_reach(const LineTile& tile, LineVertex a, LineVertex b,
                            const std::function<void(uint32_t cell)>& fn);

// Fills tile.cell_offsets / cell_segments from its runs, grid and reach.
void build_cluster_grid(LineTile& tile);

}  // namespace tileformat
