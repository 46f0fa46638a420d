// A quantized-mesh tile sampled on a block's grid (see mesh_grid.hpp): each
// triangle walks the grid points of its bounding box and claims those it
// holds. All geometry is in integers: vertex (u, v) scaled by (B - 1) f and
// grid point (i, j) at (i * 32767 f, row j's v scaled alike) — exact for
// evenly spaced rows — so the 64-bit orientation tests decide containment
// exactly and a zero weight really means "on that edge".
#include "data/mesh_grid.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

namespace globe::viewer {
namespace {

struct Point {
  int64_t x = 0, y = 0;
};

// Twice the signed area of (a, b, p): > 0 when p is left of a -> b.
int64_t orient(Point a, Point b, Point p) {
  return (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x);
}

int64_t floor_div(int64_t a, int64_t b) {
  return a >= 0 ? a / b : -((-a + b - 1) / b);
}
int64_t ceil_div(int64_t a, int64_t b) {
  return -floor_div(-a, b);
}

// Height at p on the segment p0 p1 (p on it): the endpoints in one order
// whatever the triangle or tile, the parameter along the axis they differ in.
double on_edge(Point p, Point p0, double h0, Point p1, double h1) {
  if (p1.x < p0.x || (p1.x == p0.x && p1.y < p0.y)) {
    std::swap(p0, p1);
    std::swap(h0, h1);
  }
  const double t = p1.x != p0.x ? double(p.x - p0.x) / double(p1.x - p0.x)
                                : double(p.y - p0.y) / double(p1.y - p0.y);
  return h0 + (h1 - h0) * t;
}

}  // namespace

std::vector<float> mesh_grid(const QuantizedMesh& mesh, int block_size,
                             std::span<const double> row_v) {
  if (block_size < 2 || block_size > 4097)
    throw std::invalid_argument("mesh_grid: block size " + std::to_string(block_size) +
                                " outside 2..4097");
  if (!row_v.empty() && row_v.size() != size_t(block_size))
    throw std::invalid_argument("mesh_grid: " + std::to_string(row_v.size()) +
                                " row positions for " + std::to_string(block_size) + " rows");
  const int64_t steps = block_size - 1, q = kQuantizedMeshMax;
  // Vertices at (u, v) * steps * f, grid columns at i * q * f: integers, at
  // most 1e9, so orientations (products of two differences) stay below 2^62.
  const int64_t f = std::max<int64_t>(1, 1'000'000'000 / (q * steps));
  const size_t side = size_t(block_size);
  std::vector<int64_t> row_y(side);  // descending: row 0 is the north edge
  for (size_t j = 0; j < side; ++j) {
    if (row_v.empty()) {
      row_y[j] = (steps - int64_t(j)) * q * f;
      continue;
    }
    const double v = row_v[j];
    if (!(v >= 0 && v <= q) || (j > 0 && v > row_v[j - 1]))
      throw std::invalid_argument("mesh_grid: row positions must fall from 32767 to 0");
    row_y[j] = std::llround(v * double(steps * f));
  }
  std::vector<float> grid(side * side, std::numeric_limits<float>::quiet_NaN());
  std::vector<uint8_t> done(side * side, 0);
  std::vector<double> h(mesh.vertex_count());
  for (size_t k = 0; k < h.size(); ++k)
    h[k] = mesh.height_m(k);
  const auto vertex = [&](uint32_t k) {
    return Point{mesh.u[k] * steps * f, mesh.v[k] * steps * f};
  };

  for (size_t t = 0; t + 2 < mesh.triangles.size(); t += 3) {
    uint32_t ia = mesh.triangles[t], ib = mesh.triangles[t + 1], ic = mesh.triangles[t + 2];
    Point a = vertex(ia), b = vertex(ib), c = vertex(ic);
    int64_t area = orient(a, b, c);
    if (area == 0) continue;  // degenerate: its points belong to its neighbours
    if (area < 0) {           // the spec's triangles are counter-clockwise; accept either
      std::swap(b, c);
      std::swap(ib, ic);
      area = -area;
    }
    // Grid points inside the bounding box: columns x = i * q * f, rows by row_y.
    const int64_t i0 = ceil_div(std::min({a.x, b.x, c.x}), q * f);
    const int64_t i1 = floor_div(std::max({a.x, b.x, c.x}), q * f);
    const int64_t y_max = std::max({a.y, b.y, c.y}), y_min = std::min({a.y, b.y, c.y});
    const size_t j0 = size_t(
        std::partition_point(row_y.begin(), row_y.end(), [&](int64_t y) { return y > y_max; }) -
        row_y.begin());
    const size_t j1 = size_t(
        std::partition_point(row_y.begin(), row_y.end(), [&](int64_t y) { return y >= y_min; }) -
        row_y.begin());
    for (size_t j = j0; j < j1; ++j)
      for (int64_t i = std::max<int64_t>(i0, 0); i <= std::min(i1, steps); ++i) {
        const size_t at = j * side + size_t(i);
        if (done[at]) continue;
        const Point p{i * q * f, row_y[j]};
        const int64_t wa = orient(b, c, p), wb = orient(c, a, p), wc = orient(a, b, p);
        if (wa < 0 || wb < 0 || wc < 0) continue;
        double height;
        if (wa == area)
          height = h[ia];
        else if (wb == area)
          height = h[ib];
        else if (wc == area)
          height = h[ic];
        else if (wa == 0)
          height = on_edge(p, b, h[ib], c, h[ic]);
        else if (wb == 0)
          height = on_edge(p, c, h[ic], a, h[ia]);
        else if (wc == 0)
          height = on_edge(p, a, h[ia], b, h[ib]);
        else
          height = (double(wa) * h[ia] + double(wb) * h[ib] + double(wc) * h[ic]) / double(area);
        grid[at] = static_cast<float>(height);
        done[at] = 1;
      }
  }
  return grid;
}

std::vector<double> mercator_row_v(int z, uint32_t y, int block_size) {
  if (block_size < 2) throw std::invalid_argument("mercator_row_v: block size below 2");
  const double n = std::ldexp(1.0, z), steps = block_size - 1;
  const auto lat = [&](double row_from_north) {  // degrees
    return std::atan(std::sinh(std::numbers::pi * (1 - 2 * row_from_north / n))) * 180 /
           std::numbers::pi;
  };
  const double north = lat(y), south = lat(y + 1.0);
  std::vector<double> v(static_cast<size_t>(block_size));
  for (int j = 0; j < block_size; ++j)
    v[size_t(j)] = std::clamp((lat(y + j / steps) - south) / (north - south) * kQuantizedMeshMax,
                              0.0, double(kQuantizedMeshMax));
  v.front() = kQuantizedMeshMax;
  v.back() = 0;
  return v;
}

}  // namespace globe::viewer
