// Error trees: exact zero on planes, exact deviation on a bump, saturation,
// identical edge-vertex errors computed from either side of an edge, and every
// node's error on rough terrain against a brute force over the node's samples.
#include <gtest/gtest.h>

#include <random>

#include "runtime/error_tree.hpp"
#include "tileformat/kpatch.hpp"
#include "tileformat/mblock.hpp"

using tileformat::KPatchLayout;

namespace {
constexpr int kSteps = 64, kSize = kSteps + 1;

std::vector<int32_t> plane() {
  std::vector<int32_t> q(kSize * kSize);
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x)
      q[y * kSize + x] = 3 * x - 5 * y + 100;
  return q;
}
}  // namespace

TEST(ErrorTree, PlaneHasZeroError) {
  const KPatchLayout l(kSteps, 16, 0);
  const auto err = globe::node_errors(l, plane(), {}, {});
  for (uint32_t e : err)
    EXPECT_EQ(e, 0u);
}

TEST(ErrorTree, SpikeErrorIsExactAndSaturatedUpwards) {
  const KPatchLayout l(kSteps, 16, 1);
  auto q = plane();
  q[34 * kSize + 31] += 40;  // x + y odd: a lattice vertex of the leaves only
  const auto err = globe::node_errors(l, q, {}, {});
  uint32_t root = std::max(err[0], err[1]);
  EXPECT_EQ(root, 40u);
  for (const auto& n : l.nodes())
    if (n.children[0] >= 0) {
      const size_t i = &n - l.nodes().data();
      EXPECT_GE(err[i], err[n.children[0]]);
      EXPECT_GE(err[i], err[n.children[1]]);
    }
}

TEST(ErrorTree, InvalidSamplesDoNotCount) {
  const KPatchLayout l(kSteps, 16, 0);
  auto q = plane();
  q[34 * kSize + 31] += 40;
  std::vector<uint8_t> valid(q.size(), 1);
  valid[34 * kSize + 31] = 0;
  const auto err = globe::node_errors(l, q, valid, {});
  // The spike still bends the lattice of coarse nodes only if it is a lattice
  // vertex; here it is not, so with the sample masked every error is zero.
  EXPECT_EQ(std::max(err[0], err[1]), 0u);
}

TEST(ErrorTree, EdgeVertexErrorsMatchAcrossNeighbours) {
  std::mt19937 rng(7);
  // Two blocks side by side (A west, B east), random terrain.
  std::vector<int32_t> qa(kSize * kSize), qb(kSize * kSize);
  for (auto& v : qa)
    v = static_cast<int32_t>(rng() % 200);
  for (auto& v : qb)
    v = static_cast<int32_t>(rng() % 200);
  for (int y = 0; y < kSize; ++y)
    qb[y * kSize] = qa[y * kSize + kSteps];
  const KPatchLayout la(kSteps, 16, 0), lb(kSteps, 16, 1);
  const auto ea = globe::node_errors(la, qa, {}, {}), eb = globe::node_errors(lb, qb, {}, {});
  globe::Neighbourhood na{}, nb{};
  na[1][1] = &ea;
  na[1][2] = &eb;
  nb[1][1] = &eb;
  nb[1][0] = &ea;
  const auto va = globe::vertex_errors(la, na), vb = globe::vertex_errors(lb, nb);
  for (int m = 0; m < la.depth() / 2; ++m)
    for (int c = 0; c < (1 << m); ++c)
      EXPECT_EQ(va[la.vedge_vertex(m, c, 1 << m)], vb[lb.vedge_vertex(m, c, 0)])
          << "level " << m << " edge " << c;
  // Saturation: a cell centre is >= its four edge midpoints.
  for (int m = 0; m < la.depth() / 2; ++m)
    for (int cy = 0; cy < (1 << m); ++cy)
      for (int cx = 0; cx < (1 << m); ++cx) {
        const uint32_t centre = va[la.cell_vertex(m, cx, cy)];
        EXPECT_GE(centre, va[la.hedge_vertex(m, cy, cx)]);
        EXPECT_GE(centre, va[la.hedge_vertex(m, cy + 1, cx)]);
        EXPECT_GE(centre, va[la.vedge_vertex(m, cy, cx)]);
        EXPECT_GE(centre, va[la.vedge_vertex(m, cy, cx + 1)]);
      }
}

namespace {

// Brute force: each node's error is the largest |surface - sample| over the
// valid samples in its closed triangle, rounded up to whole quanta, and then
// the largest of its own and its descendants'. The surface is the node's
// lattice (L steps along each leg, every cell split along the diagonal from
// its second to its third corner); each sample is located by solving for its
// lattice coordinates, so cell edges need no ownership rules (the surface is
// continuous). Exact: coordinates times ww = |leg step|^2 are integers, and
// 64 bits hold every product for these 65 x 65 blocks (ww <= 16).
std::vector<uint32_t> brute_force_errors(const KPatchLayout& l, const std::vector<int32_t>& q,
                                         const std::vector<uint8_t>& valid) {
  const int size = l.steps() + 1, L = l.lattice();
  const auto& nodes = l.nodes();
  std::vector<uint32_t> err(nodes.size(), 0);
  for (size_t i = 0; i < nodes.size(); ++i) {
    const auto& n = nodes[i];
    if (n.depth == l.depth()) continue;  // draws every sample
    const int ux = (n.b.x - n.apex.x) / L, uy = (n.b.y - n.apex.y) / L;
    const int vx = (n.c.x - n.apex.x) / L, vy = (n.c.y - n.apex.y) / L;
    const int64_t ww = ux * ux + uy * uy;
    auto h = [&](int64_t ci, int64_t cj) {
      return int64_t{q[(n.apex.y + ci * uy + cj * vy) * size + n.apex.x + ci * ux + cj * vx]};
    };
    int64_t worst = 0;
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x) {
        if (!valid.empty() && !valid[y * size + x]) continue;
        const int64_t a = int64_t{x - n.apex.x} * ux + int64_t{y - n.apex.y} * uy;
        const int64_t b = int64_t{x - n.apex.x} * vx + int64_t{y - n.apex.y} * vy;
        if (a < 0 || b < 0 || a + b > L * ww) continue;  // outside the triangle
        int64_t ci = std::min<int64_t>(a / ww, L - 1), cj = std::min<int64_t>(b / ww, L - 1);
        if (ci + cj > L - 1) {  // on the hypotenuse: the cell below it
          if (ci > 0)
            --ci;
          else
            --cj;
        }
        const int64_t fa = a - ci * ww, fb = b - cj * ww;  // in [0, ww]
        int64_t surface;                                   // times ww
        if (fa + fb <= ww)
          surface =
              h(ci, cj) * ww + fa * (h(ci + 1, cj) - h(ci, cj)) + fb * (h(ci, cj + 1) - h(ci, cj));
        else
          surface = h(ci + 1, cj + 1) * ww + (ww - fb) * (h(ci + 1, cj) - h(ci + 1, cj + 1)) +
                    (ww - fa) * (h(ci, cj + 1) - h(ci + 1, cj + 1));
        int64_t d = surface - int64_t{q[y * size + x]} * ww;
        worst = std::max(worst, d < 0 ? -d : d);
      }
    err[i] = static_cast<uint32_t>((worst + ww - 1) / ww);
  }
  for (size_t i = nodes.size(); i-- > 0;)  // children follow their parents
    for (int32_t c : nodes[i].children)
      if (c >= 0) err[i] = std::max(err[i], err[c]);
  return err;
}

// Random heights within +-amplitude, or (bowl) a paraboloid of that depth
// with +-3 quanta of noise: there the coarse nodes' own errors are the
// largest, so saturation from below cannot hide a wrong one.
void expect_brute_force(int32_t amplitude, unsigned seed, bool holes, bool bowl = false) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int32_t> height(-amplitude, amplitude), noise(-3, 3);
  std::vector<int32_t> q(kSize * kSize);
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      const double r2 = (x - 29.0) * (x - 29.0) + (y - 37.0) * (y - 37.0);
      q[y * kSize + x] =
          bowl ? static_cast<int32_t>(amplitude * (r2 / 4096.0 - 1.0)) + noise(rng) : height(rng);
    }
  std::vector<uint8_t> valid;
  if (holes) {
    valid.assign(q.size(), 1);
    for (auto& v : valid)
      v = rng() % 5 != 0;
  }
  for (int diagonal : {0, 1}) {
    const KPatchLayout l(kSteps, 16, diagonal);
    const auto got = globe::node_errors(l, q, valid, {});
    const auto want = brute_force_errors(l, q, valid);
    ASSERT_EQ(got.size(), want.size());
    for (size_t i = 0; i < got.size(); ++i)
      ASSERT_EQ(got[i], want[i]) << "node " << i << " depth " << l.nodes()[i].depth
                                 << ", heights within +-" << amplitude << (bowl ? " (bowl)" : "");
  }
}

}  // namespace

// Heights of a few metres, of tens of kilometres at a centimetre step (the
// arithmetic in 32 bits at every depth), of 2^25 quanta (64 bits at the
// coarsest depths, 32 below) and of the largest quantum the format allows.
TEST(ErrorTree, EveryNodeMatchesBruteForceOnRoughTerrain) {
  expect_brute_force(300, 1, false);
  expect_brute_force(300, 8, false, true);
  expect_brute_force(int32_t{1} << 28, 9, false, true);
  expect_brute_force(3'000'000, 2, false);
  expect_brute_force(int32_t{1} << 25, 3, false);
  expect_brute_force(tileformat::kMaxQuantum, 4, false);
}

TEST(ErrorTree, EveryNodeMatchesBruteForceWithHoles) {
  expect_brute_force(300, 5, true);
  expect_brute_force(300, 10, true, true);
  expect_brute_force(int32_t{1} << 25, 6, true);
  expect_brute_force(tileformat::kMaxQuantum, 7, true);
}
