// Sky-view factor (see sky_view.hpp).
#include "analysis/sky_view.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

namespace globe {
namespace {

// Steps 1..kFineSteps are one sample apart; further out each is kGrowth
// times the distance of the last (a horizon far away changes slowly with
// distance, so this keeps a ray at ~60 steps for 10 km over 30 m samples).
constexpr int kFineSteps = 12;
constexpr double kGrowth = 1.07;

double snap(double v) {
  const double r = std::round(v);
  return std::abs(v - r) < 1e-9 ? r : v;
}

// The two per-step loops over a row's samples, nearly all of the sky view's
// time. Their reads and writes stay within [0, n] of each pointer, which
// SkyViewScan::row checks once per step against the height window's bounds;
// they are left out of the sanitizers' per-access instrumentation, which made
// the sky view 7 times slower under ASan + UBSan than with it left out (27.9
// against 3.9 CPU s on jacksboro; docs/ci.md). The same bytes either way.
#define GLOBE_CHECKED_KERNEL __attribute__((no_sanitize("address", "undefined")))

// Samples whose step lands where any of the four heights it interpolates has
// no data end their rays there (kNever added from then on).
GLOBE_CHECKED_KERNEL void end_rays(const uint8_t* v0, const uint8_t* v1, float* ended, size_t n,
                                   float never) {
  for (size_t x = 0; x < n; ++x)
    ended[x] = (v0[x] & v0[x + 1] & v1[x] & v1[x + 1]) ? ended[x] : never;
}

// best[x] = max(best[x], the tangent of the step's elevation seen from
// sample x, + ended[x]); the step lies between rows r0 and r1, tx and ty of
// the way from sample x to x + 1 and from r0 to r1.
GLOBE_CHECKED_KERNEL void step_tangents(const float* r0, const float* r1, const float* h0,
                                        const float* ended, float* best, size_t n, float tx,
                                        float ty, float inv) {
  for (size_t x = 0; x < n; ++x) {
    const float top = r0[x] + tx * (r0[x + 1] - r0[x]);
    const float bottom = r1[x] + tx * (r1[x + 1] - r1[x]);
    const float t = (top + ty * (bottom - top) - h0[x]) * inv + ended[x];
    best[x] = t > best[x] ? t : best[x];  // std::max is not inlined into an uninstrumented function
  }
}

#undef GLOBE_CHECKED_KERNEL

}  // namespace

SkyViewReach sky_view_reach(const SkyViewSettings& s, double min_spacing_m, int steps,
                            int coarser_zooms) {
  SkyViewReach r;
  for (int k = 0; k <= coarser_zooms; ++k) {
    const double spacing = std::ldexp(min_spacing_m, k);  // metres per sample of level k
    const double wanted = std::ceil(s.radius_m / spacing) + 1;
    const int halo = static_cast<int>(std::min<double>(wanted, 2.0 * steps));
    r.halos.push_back(halo);
    // A sample on the block's edge has halo - 1 whole steps of bilinear
    // neighbourhoods beyond it (HeightLevels::height).
    r.radius_m = std::min(s.radius_m, (halo - 1) * spacing);
    if (halo == wanted) break;
  }
  return r;
}

SkyViewScan::SkyViewScan(const SkyViewSettings& s, GroundSpacing sp) {
  for (int k = 0; k < s.directions; ++k) {
    const double az = 2 * std::numbers::pi * k / s.directions;           // clockwise from north
    const double ex = std::sin(az) / sp.dx, ey = -std::cos(az) / sp.dy;  // samples per metre
    // One sample along the ray's major axis; never past the radius, so that
    // a zoom coarser than the radius still sees the slope of its own cells.
    const double unit = std::min(1 / std::max(std::abs(ex), std::abs(ey)), s.radius_m);
    std::vector<Step> ray;
    double dist = 0;
    for (int j = 1;; ++j) {
      dist = j <= kFineSteps ? unit * j : dist * kGrowth;
      if (dist > s.radius_m * (1 + 1e-9)) break;
      // Offsets a rounding error away from a whole sample (the diagonals'
      // first steps) are that sample, so that which samples a step reads
      // (and where a ray ends at no data) does not hang on the last bit.
      const double dx = snap(ex * dist), dy = snap(ey * dist);
      const int ix = static_cast<int>(std::floor(dx)), iy = static_cast<int>(std::floor(dy));
      ray.push_back({dx, dy, 1 / dist, ix, iy, dx - ix, dy - iy});
    }
    rays_.push_back(std::move(ray));
  }
}

void SkyViewScan::row(const HeightLevels& levels, int y, int size, double* out) const {
  const HeightWindow& w = levels.own();
  const int halo = w.halo();
  const float* h0 = w.row(y);
  const size_t n = static_cast<size_t>(size);
  constexpr float kNever = -std::numeric_limits<float>::infinity();
  std::vector<double> sum(n, 0.0);
  std::vector<float> best(n);  // tangents: single precision, like the heights
  // Added to a sample's tangents: 0, or kNever once its ray has ended at no
  // data (so that the whole row's step stays one branch-free loop).
  std::vector<float> ended(n);
  // Per sample, the step at which its ray left the block's own zoom, or
  // kAtOwnZoom while it has not.
  std::vector<size_t> left(n);
  constexpr size_t kAtOwnZoom = std::numeric_limits<size_t>::max();
  for (const auto& ray : rays_) {
    int a = 0, b = size - 1;  // the samples whose rays are still at their own zoom
    for (size_t x = 0; x < n; ++x) {
      best[x] = 0;
      ended[x] = w.valid(int(x), y) ? 0 : kNever;
      left[x] = kAtOwnZoom;
    }
    for (size_t j = 0; j < ray.size() && a <= b; ++j) {
      const Step& s = ray[j];
      const int yy = y + s.iy;
      int lo = 1, hi = 0;  // x whose neighbourhood lies inside the window
      if (yy >= -halo && yy + 1 <= size - 1 + halo) {
        lo = std::max(a, -halo - s.ix);
        hi = std::min(b, size - 2 + halo - s.ix);
      }
      // The ray moves monotonically away: samples out of the window now
      // stay out (their rays go on in the coarser zooms, below).
      for (int x = a; x <= b; ++x) {
        if (x >= lo && x <= hi) {
          x = hi;
          continue;
        }
        left[size_t(x)] = j;
      }
      a = lo;
      b = hi;
      if (a > b) break;
      const float tx = float(s.tx), ty = float(s.ty), inv = float(s.inv_distance);
      const int c0 = a + s.ix, c1 = b + s.ix + 1;  // the window columns read
      // What the kernels touch: samples a..b of the row's vectors, columns
      // c0..c1 of window rows yy and yy + 1.
      if (a < 0 || b >= size || c0 < -halo || c1 > size - 1 + halo || yy < -halo ||
          yy + 1 > size - 1 + halo)
        throw std::logic_error("sky view: a ray step leaves the height window");
      const size_t count = size_t(b - a + 1);
      if (!w.all_valid(yy, c0, c1) || !w.all_valid(yy + 1, c0, c1))
        end_rays(w.valid_row(yy) + c0, w.valid_row(yy + 1) + c0, ended.data() + a, count, kNever);
      step_tangents(w.row(yy) + c0, w.row(yy + 1) + c0, h0 + a, ended.data() + a, best.data() + a,
                    count, tx, ty, inv);
    }
    for (size_t x = 0; x < n; ++x) {
      if (ended[x] == 0 && left[x] != kAtOwnZoom) {  // on in the coarser zooms
        int level = 1;
        for (size_t j = left[x]; j < ray.size(); ++j) {
          const Step& s = ray[j];
          double h = 0;
          if (levels.height(double(x) + s.dx, y + s.dy, level, h) != HeightLevels::Sample::kHeight)
            break;
          best[x] = std::max(best[x], float((h - h0[x]) * s.inv_distance));
        }
      }
      const double t = best[x];
      sum[x] += t / std::sqrt(1 + t * t);  // sin(atan(t))
    }
  }
  for (int x = 0; x < size; ++x)
    out[x] = w.valid(x, y) ? 1 - sum[size_t(x)] / static_cast<double>(rays_.size())
                           : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace globe
