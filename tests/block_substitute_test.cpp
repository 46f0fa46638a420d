// Stand-ins for broken terrain blocks (viewer/data/block_substitute.hpp)
// against a surface evaluated in the test: f is bilinear in the parent's
// sample coordinates, so a parent's samples are f there, a child's are f at
// half steps, and bilinear interpolation reproduces f exactly.
#include <gtest/gtest.h>

#include <optional>
#include <stdexcept>

#include "data/block_substitute.hpp"

namespace {

using globe::viewer::from_children;
using globe::viewer::from_parent;
using globe::viewer::SampleGrid;
using globe::viewer::Stand;
using globe::viewer::substitute_grid;
using globe::viewer::SubstituteSource;
using tileformat::TileId;

constexpr int kSize = 9;  // 8 steps a block

double f(double x, double y) {  // x, y: parent samples from its north-west corner
  return 100 + 3 * x + 7 * y + 0.5 * x * y;
}

// Tile (qx, qy) of the quadrants below the parent: its samples are at parent
// coordinates (qx * 4 + i / 2, qy * 4 + j / 2).
SampleGrid child(int qx, int qy) {
  SampleGrid g{kSize, 1, {}, std::vector<uint8_t>(kSize * kSize, 255)};
  for (int j = 0; j < kSize; ++j)
    for (int i = 0; i < kSize; ++i)
      g.values.push_back(float(f(qx * 4 + i / 2.0, qy * 4 + j / 2.0)));
  return g;
}

SampleGrid parent() {
  SampleGrid g{kSize, 1, {}, std::vector<uint8_t>(kSize * kSize, 255)};
  for (int j = 0; j < kSize; ++j)
    for (int i = 0; i < kSize; ++i)
      g.values.push_back(float(f(i, j)));
  return g;
}

TEST(BlockSubstitute, ChildrenGiveTheParentsSamplesExactly) {
  std::optional<SampleGrid> kids[2][2] = {{child(0, 0), child(1, 0)}, {child(0, 1), std::nullopt}};
  const SampleGrid g = from_children(kids, kSize, 1);
  for (int j = 0; j < kSize; ++j)
    for (int i = 0; i < kSize; ++i) {
      const size_t k = size_t(j) * kSize + i;
      const bool south_east = i > 4 && j > 4;  // only the missing child holds these
      EXPECT_EQ(g.mask[k], south_east ? 0 : 255) << i << "," << j;
      if (!south_east) {
        EXPECT_FLOAT_EQ(g.values[k], float(f(i, j))) << i << "," << j;
      }
    }
}

TEST(BlockSubstitute, AParentQuadrantInterpolatesToTheChildsSamples) {
  const SampleGrid p = parent();
  for (int qy = 0; qy < 2; ++qy)
    for (int qx = 0; qx < 2; ++qx) {
      const SampleGrid g = from_parent(p, qx, qy);
      const SampleGrid want = child(qx, qy);
      for (size_t k = 0; k < g.values.size(); ++k) {
        EXPECT_NEAR(g.values[k], want.values[k], 1e-3) << qx << "," << qy << " sample " << k;
        EXPECT_EQ(g.mask[k], 255);
      }
    }
}

// Children first, one level further where a child is broken too; the parent
// (or its parent) at the finest zoom; nothing where neither can be read.
TEST(BlockSubstitute, ChildrenFirstThenTheParent) {
  // Zooms 0..2; tile 1/0/0 broken, and its child 2/1/1 too.
  auto read = [](TileId t) -> std::optional<SampleGrid> {
    if ((t.z == 1 && t.x == 0 && t.y == 0) || (t.z == 2 && t.x == 1 && t.y == 1))
      throw std::runtime_error("broken");
    if (t.z == 0) return parent();
    return child(int(t.x % 2), int(t.y % 2));
  };
  const SubstituteSource s{kSize, 0, 2, read};
  const auto [a, from_a] = substitute_grid(s, {1, 0, 0});
  ASSERT_TRUE(a);
  EXPECT_EQ(from_a, Stand::kChildren);
  // 2/1/1 (broken, at the finest zoom: no children) leaves its quadrant a hole.
  EXPECT_EQ(a->mask[size_t(8) * kSize + 8], 0);
  EXPECT_EQ(a->mask[0], 255);
  const auto [b, from_b] = substitute_grid(s, {2, 1, 1});
  ASSERT_TRUE(b);
  EXPECT_EQ(from_b, Stand::kParent) << "1/0/0 is broken: remade from 0/0/0";
  EXPECT_NEAR(b->values[0], f(2, 2), 1e-3) << "2/1/1's first sample lies at 0/0/0's (2, 2)";
  const SubstituteSource lone{
      kSize, 0, 0, [](TileId) -> std::optional<SampleGrid> { throw std::runtime_error("broken"); }};
  EXPECT_EQ(substitute_grid(lone, {0, 0, 0}).second, Stand::kNone);
}

}  // namespace
