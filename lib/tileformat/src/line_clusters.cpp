// Cluster-grid rule (docs/tileformat.md §7.3; see line_clusters.hpp).
#include "tileformat/line_clusters.hpp"

#include <algorithm>
#include <cmath>

namespace tileformat {
namespace {

double point_rect_distance(double px, double py, double x0, double y0, double x1, double y1) {
  const double dx = std::max({x0 - px, 0.0, px - x1});
  const double dy = std::max({y0 - py, 0.0, py - y1});
  return std::hypot(dx, dy);
}

}  // namespace

bool clip_parameters(double ax, double ay, double bx, double by, double x0, double y0, double x1,
                     double y1, double& t0, double& t1) {
  t0 = 0;
  t1 = 1;
  const double dx = bx - ax, dy = by - ay;
  const double p[4] = {-dx, dx, -dy, dy};
  const double q[4] = {ax - x0, x1 - ax, ay - y0, y1 - ay};
  for (int i = 0; i < 4; ++i) {
    if (p[i] == 0) {
      if (q[i] < 0) return false;
      continue;
    }
    const double t = q[i] / p[i];
    if (p[i] < 0)
      t0 = std::max(t0, t);
    else
      t1 = std::min(t1, t);
    if (t0 > t1) return false;
  }
  return true;
}

double point_segment_distance(double px, double py, LineVertex a, LineVertex b) {
  const double dx = double(b.x) - a.x, dy = double(b.y) - a.y;
  const double len2 = dx * dx + dy * dy;
  double t = len2 > 0 ? ((px - a.x) * dx + (py - a.y) * dy) / len2 : 0;
  t = std::clamp(t, 0.0, 1.0);
  return std::hypot(px - (a.x + t * dx), py - (a.y + t * dy));
}

double segment_rect_distance(LineVertex a, LineVertex b, double x0, double y0, double x1,
                             double y1) {
  double t0, t1;
  if (clip_parameters(a.x, a.y, b.x, b.y, x0, y0, x1, y1, t0, t1)) return 0;
  return std::min({point_rect_distance(a.x, a.y, x0, y0, x1, y1),
                   point_rect_distance(b.x, b.y, x0, y0, x1, y1),
                   point_segment_distance(x0, y0, a, b), point_segment_distance(x1, y0, a, b),
                   point_segment_distance(x0, y1, a, b), point_segment_distance(x1, y1, a, b)});
}

void for_each_cell_in_reach(const LineTile& tile, LineVertex a, LineVertex b,
                            const std::function<void(uint32_t cell)>& fn) {
  const int n = static_cast<int>(tile.grid);
  const double cs = double(tile.extent) / n, r = tile.reach;
  auto cell_index = [&](double v) {
    return static_cast<int>(std::clamp(std::floor(v / cs), -1.0, double(n)));
  };
  const int cx0 = std::max(0, cell_index(std::min(a.x, b.x) - r));
  const int cx1 = std::min(n - 1, cell_index(std::max(a.x, b.x) + r));
  const int cy0 = std::max(0, cell_index(std::min(a.y, b.y) - r));
  const int cy1 = std::min(n - 1, cell_index(std::max(a.y, b.y) + r));
  for (int cy = cy0; cy <= cy1; ++cy)
    for (int cx = cx0; cx <= cx1; ++cx)
      if (segment_rect_distance(a, b, cx * cs, cy * cs, (cx + 1) * cs, (cy + 1) * cs) <= r)
        fn(static_cast<uint32_t>(cy * n + cx));
}

void build_cluster_grid(LineTile& tile) {
  const size_t cells = size_t{tile.grid} * tile.grid;
  std::vector<std::vector<uint32_t>> lists(cells);
  uint32_t seg = 0;
  for (const LineRun& run : tile.runs) {
    for (uint32_t i = 0; i + 1 < run.vertex_count; ++i, ++seg) {
      const LineVertex a = tile.vertices[run.first_vertex + i];
      const LineVertex b = tile.vertices[run.first_vertex + i + 1];
      for_each_cell_in_reach(tile, a, b, [&](uint32_t c) { lists[c].push_back(seg); });
    }
  }
  tile.cell_offsets.assign(cells + 1, 0);
  tile.cell_segments.clear();
  for (size_t c = 0; c < cells; ++c) {
    tile.cell_segments.insert(tile.cell_segments.end(), lists[c].begin(), lists[c].end());
    tile.cell_offsets[c + 1] = static_cast<uint32_t>(tile.cell_segments.size());
  }
}

}  // namespace tileformat
