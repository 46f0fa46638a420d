// Quantized-mesh triangle errors with a limit (tools/common/web/terrain_mesh.hpp):
// the export and the server compute each zoom's errors only as far as its one
// threshold needs (bounds from the children within it, scans stopped past
// it). Checked here on random 3 x 3 tile neighbourhoods: the cut at that
// threshold is the cut of the exact errors, triangle for triangle, and every
// kept triangle is within the threshold of every sample under it (a brute
// force over the samples, written here).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <vector>

#include "web/terrain_mesh.hpp"

namespace {

using globe::web::cut_mesh;
using globe::web::GridPoint;
using globe::web::MeshErrors;
using globe::web::own_errors;
using globe::web::TileGrid;

constexpr int kSteps = 64;
constexpr double kSampleMetres = 1.0;  // sagittas below 0.1 mm: the planes decide

// Heights of a (3n + 1)^2 field: a slope, smooth hills, noise of `rough`
// metres and a few spikes (a peak a coarse triangle hides).
std::vector<double> field(std::mt19937& rng, double rough) {
  const int m = 3 * kSteps + 1;
  std::uniform_real_distribution<double> u(0, 1);
  const double fx = u(rng) * 0.2, fy = u(rng) * 0.2, slope = u(rng) * 3;
  std::vector<double> h(size_t(m) * m);
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < m; ++i)
      h[size_t(j) * m + i] =
          slope * i + 40 * std::sin(fx * i) * std::cos(fy * j) + rough * (u(rng) - 0.5);
  for (int k = 0; k < 6; ++k)
    h[size_t(rng() % (size_t(m) * m))] += 30 * u(rng);
  return h;
}

TileGrid tile(const std::vector<double>& h, int tx, int ty) {
  const int m = 3 * kSteps + 1;
  TileGrid g(kSteps, (tx + ty) & 1);
  for (int j = 0; j <= kSteps; ++j)
    for (int i = 0; i <= kSteps; ++i)
      g.at(i, j) = h[size_t(ty * kSteps + j) * m + size_t(tx * kSteps + i)];
  return g;
}

MeshErrors centre_errors(const std::vector<double>& h, double limit) {
  std::array<std::vector<float>, 9> own;
  std::array<const std::vector<float>*, 9> ptr{};
  for (int k = 0; k < 9; ++k) {
    own[size_t(k)] = own_errors(tile(h, k % 3, k / 3), kSampleMetres, limit);
    ptr[size_t(k)] = &own[size_t(k)];
  }
  return MeshErrors(kSteps, (1 + 1) & 1, ptr);
}

// The largest |height - plane| over the samples in triangle a b c.
double brute_error(const TileGrid& g, const std::array<GridPoint, 3>& t) {
  const GridPoint &a = t[0], &b = t[1], &c = t[2];
  const double area = double(b.i - a.i) * (c.j - a.j) - double(b.j - a.j) * (c.i - a.i);
  double worst = 0;
  for (int j = std::min({a.j, b.j, c.j}); j <= std::max({a.j, b.j, c.j}); ++j)
    for (int i = std::min({a.i, b.i, c.i}); i <= std::max({a.i, b.i, c.i}); ++i) {
      const double wb = (double(i - a.i) * (c.j - a.j) - double(j - a.j) * (c.i - a.i)) / area;
      const double wc = (double(b.i - a.i) * (j - a.j) - double(b.j - a.j) * (i - a.i)) / area;
      const double wa = 1 - wb - wc;
      if (wa < -1e-12 || wb < -1e-12 || wc < -1e-12) continue;
      const double plane = wa * g.at(a.i, a.j) + wb * g.at(b.i, b.j) + wc * g.at(c.i, c.j);
      worst = std::max(worst, std::fabs(g.at(i, j) - plane));
    }
  return worst;
}

TEST(MeshErrors, CutAtTheLimitIsTheCutOfTheExactErrors) {
  std::mt19937 rng(11);
  int cases = 0, triangles = 0;
  for (const double rough : {0.0, 0.5, 4.0, 40.0})
    for (int trial = 0; trial < 3; ++trial) {
      const std::vector<double> h = field(rng, rough);
      const MeshErrors exact = centre_errors(h, INFINITY);
      const TileGrid centre = tile(h, 1, 1);
      for (const double threshold : {0.25, 1.0, 2.0, 8.0, 60.0}) {
        SCOPED_TRACE("rough " + std::to_string(rough) + ", threshold " + std::to_string(threshold));
        const auto want = cut_mesh(exact, threshold);
        const auto got = cut_mesh(centre_errors(h, threshold), threshold);
        ASSERT_EQ(got.size(), want.size());
        for (size_t k = 0; k < got.size(); ++k)
          for (int v = 0; v < 3; ++v) {
            ASSERT_EQ(got[k][size_t(v)].i, want[k][size_t(v)].i) << "triangle " << k;
            ASSERT_EQ(got[k][size_t(v)].j, want[k][size_t(v)].j) << "triangle " << k;
          }
        for (const auto& t : got)
          ASSERT_LE(brute_error(centre, t), threshold + 1e-9)
              << "(" << t[0].i << "," << t[0].j << ") (" << t[1].i << "," << t[1].j << ") ("
              << t[2].i << "," << t[2].j << ")";
        ++cases, triangles += int(got.size());
      }
    }
  // Coarse and fine cuts both: from two triangles to thousands.
  EXPECT_EQ(cases, 60);
  EXPECT_GT(triangles, 20000);
}

}  // namespace
