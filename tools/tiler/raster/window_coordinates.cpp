// Interpolated window coordinates (see window_coordinates.hpp).
#include "raster/window_coordinates.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace globe {
namespace {

// Cubic Lagrange weights for nodes at -1, 0, 1, 2 (in cell units) at u in [0, 1).
std::array<double, 4> cubic_weights(double u) {
  return {-u * (u - 1) * (u - 2) / 6, (u + 1) * (u - 1) * (u - 2) / 2, -(u + 1) * u * (u - 2) / 2,
          (u + 1) * u * (u - 1) / 6};
}

}  // namespace

WindowCoordinates::WindowCoordinates(GDALTransformerFunc transform, void* arg, int w, int h,
                                     double tolerance_px, const Extent& clip)
    : transform_(transform), arg_(arg), w_(w), h_(h) {
  // Node k sits at pixel (k - 1) * kCell: one node before the window and two
  // past its last cell, so every cell has the 4 x 4 nodes cubic
  // interpolation needs.
  cells_x_ = (w + kCell - 1) / kCell;
  cells_y_ = (h + kCell - 1) / kCell;
  nodes_x_ = cells_x_ + 3;
  const int nodes_y = cells_y_ + 3;
  for (int i = 0; i < kCell; ++i)
    weights_[i] = cubic_weights(double(i) / kCell);

  nodes_.resize(size_t(nodes_x_) * nodes_y);
  std::vector<double> x(std::max(nodes_x_, cells_x_)), y(x.size()), z(x.size());
  std::vector<int> ok(x.size());
  for (int j = 0; j < nodes_y; ++j) {
    for (int i = 0; i < nodes_x_; ++i) {
      x[i] = (i - 1) * kCell + 0.5;
      y[i] = (j - 1) * kCell + 0.5;
      z[i] = 0;
    }
    transform_(arg_, TRUE, nodes_x_, x.data(), y.data(), z.data(), ok.data());
    for (int i = 0; i < nodes_x_; ++i)
      nodes_[size_t(j) * nodes_x_ + i] = {x[i], y[i],
                                          ok[i] && std::isfinite(x[i]) && std::isfinite(y[i])};
  }

  // Adds the part of a box of source coordinates inside `clip`.
  extent_ = {HUGE_VAL, HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  auto grow_box = [&](double x0, double y0, double x1, double y1) {
    x0 = std::max(x0, clip.min_x);
    y0 = std::max(y0, clip.min_y);
    x1 = std::min(x1, clip.max_x);
    y1 = std::min(y1, clip.max_y);
    if (x0 > x1 || y0 > y1) return;
    extent_.min_x = std::min(extent_.min_x, x0);
    extent_.max_x = std::max(extent_.max_x, x1);
    extent_.min_y = std::min(extent_.min_y, y0);
    extent_.max_y = std::max(extent_.max_y, y1);
  };

  // Cells: interpolate where the centre agrees with the exact transform.
  exact_.assign(size_t(cells_x_) * cells_y_, 1);
  std::vector<double> scale_x, scale_y;
  const int mid = kCell / 2;
  for (int cj = 0; cj < cells_y_; ++cj) {
    for (int ci = 0; ci < cells_x_; ++ci) {
      x[ci] = ci * kCell + mid + 0.5;
      y[ci] = cj * kCell + mid + 0.5;
      z[ci] = 0;
    }
    transform_(arg_, TRUE, cells_x_, x.data(), y.data(), z.data(), ok.data());
    for (int ci = 0; ci < cells_x_; ++ci) {
      bool all = ok[ci] != 0;
      double lo_x = HUGE_VAL, lo_y = HUGE_VAL, hi_x = -HUGE_VAL, hi_y = -HUGE_VAL;
      for (int m = 0; m < 4 && all; ++m)
        for (int k = 0; k < 4 && all; ++k) {
          const Node& n = node(ci + k, cj + m);
          all = n.ok != 0;
          lo_x = std::min(lo_x, n.x);
          hi_x = std::max(hi_x, n.x);
          lo_y = std::min(lo_y, n.y);
          hi_y = std::max(hi_y, n.y);
        }
      if (!all) continue;
      double ix, iy;
      interpolate(ci, cj, mid, mid, ix, iy);
      if (!(std::abs(ix - x[ci]) <= tolerance_px && std::abs(iy - y[ci]) <= tolerance_px)) continue;
      exact_[size_t(cj) * cells_x_ + ci] = 0;
      // The interpolation stays within the range of its 4 x 4 nodes (which
      // reach a cell beyond this one on every side) up to its error.
      grow_box(lo_x, lo_y, hi_x, hi_y);
      const Node &a = node(ci + 1, cj + 1), &b = node(ci + 2, cj + 1), &c = node(ci + 1, cj + 2);
      const double step_x = std::max(std::abs(b.x - a.x), std::abs(c.x - a.x)) / kCell;
      const double step_y = std::max(std::abs(b.y - a.y), std::abs(c.y - a.y)) / kCell;
      if (step_x > 0) scale_x.push_back(1 / step_x);
      if (step_y > 0) scale_y.push_back(1 / step_y);
    }
  }

  // Exact cells: every pixel once, for the extent.
  std::vector<double> rx(w), ry(w);
  std::vector<int> rok(w);
  for (int py = 0; py < h; ++py) {
    const int cj = py / kCell;
    for (int ci = 0; ci < cells_x_;) {
      if (!exact_[size_t(cj) * cells_x_ + ci]) {
        ++ci;
        continue;
      }
      int end = ci;
      while (end < cells_x_ && exact_[size_t(cj) * cells_x_ + end])
        ++end;
      const int x0 = ci * kCell, x1 = std::min(w, end * kCell);
      exact(x0, x1, py, rx.data(), ry.data(), rok.data());
      for (int i = 0; i < x1 - x0; ++i)
        if (rok[i]) grow_box(rx[i], ry[i], rx[i], ry[i]);
      ci = end;
    }
  }
  for (uint8_t e : exact_)
    exact_cells_ += e;

  // Mean scale, ignoring outliers (cells next to a discontinuity), as GDAL's
  // XSCALE=FROM_GRID_SAMPLING does.
  auto mean_step = [](const std::vector<double>& s) {
    if (s.empty()) return 0.0;
    const double top = *std::max_element(s.begin(), s.end());
    double sum = 0;
    int n = 0;
    for (double v : s)
      if (v > top / 10) {
        sum += v;
        ++n;
      }
    return n / sum;
  };
  step_x_ = mean_step(scale_x);
  step_y_ = mean_step(scale_y);
}

void WindowCoordinates::interpolate(int ci, int cj, int px, int py, double& sx, double& sy) const {
  const auto& wx = weights_[px];
  const auto& wy = weights_[py];
  sx = sy = 0;
  for (int m = 0; m < 4; ++m) {
    double rx = 0, ry = 0;
    for (int k = 0; k < 4; ++k) {
      const Node& n = node(ci + k, cj + m);
      rx += wx[k] * n.x;
      ry += wx[k] * n.y;
    }
    sx += wy[m] * rx;
    sy += wy[m] * ry;
  }
}

void WindowCoordinates::exact(int x0, int x1, int y, double* sx, double* sy, int* ok) const {
  const int n = x1 - x0;
  std::vector<double> z(n, 0.0);
  for (int i = 0; i < n; ++i) {
    sx[i] = x0 + i + 0.5;
    sy[i] = y + 0.5;
  }
  transform_(arg_, TRUE, n, sx, sy, z.data(), ok);
  for (int i = 0; i < n; ++i)
    ok[i] = ok[i] && std::isfinite(sx[i]) && std::isfinite(sy[i]);
}

void WindowCoordinates::row(int y, double* sx, double* sy, int* ok) const {
  const int cj = y / kCell;
  const auto& wy = weights_[y % kCell];
  // The four node rows of this cell row, interpolated to y once.
  thread_local std::vector<double> col_x, col_y;
  col_x.resize(nodes_x_);
  col_y.resize(nodes_x_);
  for (int k = 0; k < nodes_x_; ++k) {
    double vx = 0, vy = 0;
    for (int m = 0; m < 4; ++m) {
      const Node& n = node(k, cj + m);
      vx += wy[m] * n.x;
      vy += wy[m] * n.y;
    }
    col_x[k] = vx;
    col_y[k] = vy;
  }
  for (int ci = 0; ci < cells_x_;) {
    const int x0 = ci * kCell;
    if (exact_[size_t(cj) * cells_x_ + ci]) {
      int end = ci;
      while (end < cells_x_ && exact_[size_t(cj) * cells_x_ + end])
        ++end;
      const int x1 = std::min(w_, end * kCell);
      exact(x0, x1, y, sx + x0, sy + x0, ok + x0);
      ci = end;
      continue;
    }
    const int x1 = std::min(w_, x0 + kCell);
    const double *cx = col_x.data() + ci, *cy = col_y.data() + ci;
    for (int px = x0; px < x1; ++px) {
      const auto& wx = weights_[px - x0];
      sx[px] = wx[0] * cx[0] + wx[1] * cx[1] + wx[2] * cx[2] + wx[3] * cx[3];
      sy[px] = wx[0] * cy[0] + wx[1] * cy[1] + wx[2] * cy[2] + wx[3] * cy[3];
      ok[px] = 1;
    }
    ++ci;
  }
}

}  // namespace globe
