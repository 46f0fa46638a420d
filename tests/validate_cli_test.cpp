// globe-tiler validate must fail on packages that break the invariants it
// checks: packages are written here with deliberately wrong blocks.
#include <gtest/gtest.h>

#include "test_support.hpp"
#include "tileformat/kpatch.hpp"
#include "tileformat/mblock.hpp"
#include "tileformat/metadata.hpp"
#include "tileformat/package.hpp"
#include "tileformat/tiling.hpp"

using namespace globe_test;
using tileformat::MBlock;
using tileformat::TileId;

namespace {

constexpr int kSize = 33;

MBlock flat_block(int32_t height) {
  MBlock b;
  b.size = kSize;
  b.lattice = 16;
  b.step = 1;
  b.q.assign(kSize * kSize, height);
  b.vertex_error.assign(tileformat::kpatch_vertex_count(tileformat::kpatch_depth(kSize - 1, 16)),
                        0);
  return b;
}

// Writes a z=1 package with blocks at (1, 0, 0) and (1, 1, 0) and their parent.
std::string write_package(const TempDir& dir, const MBlock& west, const MBlock& east,
                          const MBlock& parent, std::vector<uint8_t> corrupt = {}) {
  const auto path = (dir / "p.mbtiles").string();
  tileformat::PackageWriter w(path, tileformat::IfExists::kOverwrite);
  std::map<std::string, std::string> meta;
  tileformat::Tiling::webmercator().to_metadata(meta);
  meta["format"] = tileformat::kMBlockFormat;
  meta["name"] = "p";
  meta["globe:block_size"] = std::to_string(kSize);
  meta["globe:kpatch_lattice"] = "16";
  meta["globe:height_step"] = "1";
  meta["minzoom"] = "0";
  meta["maxzoom"] = "1";
  for (const auto& [k, v] : meta)
    w.set_metadata(k, v);
  w.put_tile({1, 0, 0}, corrupt.empty() ? tileformat::encode_mblock(west) : corrupt);
  w.put_tile({1, 1, 0}, tileformat::encode_mblock(east));
  w.put_tile({0, 0, 0}, tileformat::encode_mblock(parent));
  w.commit();
  return path;
}

}  // namespace

TEST(ValidateCli, AcceptsConsistentBlocks) {
  TempDir dir;
  const auto path = write_package(dir, flat_block(5), flat_block(5), flat_block(5));
  auto r = run(tiler() + " validate " + path, dir.path());
  // Only optional metadata is missing: warnings, exit 5.
  EXPECT_EQ(r.exit_code, 5) << r.out;
  EXPECT_NE(r.out.find("0 errors"), std::string::npos) << r.out;
}

TEST(ValidateCli, DetectsDifferentSharedEdges) {
  TempDir dir;
  MBlock east = flat_block(5);
  east.q[10 * kSize] = 6;  // first column of the east block = last column of the west block
  const auto path = write_package(dir, flat_block(5), east, flat_block(5));
  auto r = run(tiler() + " validate " + path, dir.path());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.out.find("tile 1/0/0: edge sample differs from neighbour 1/1/0"), std::string::npos)
      << r.out;
}

TEST(ValidateCli, DetectsCoarseSamplesThatDifferFromFineOnes) {
  TempDir dir;
  const auto path = write_package(dir, flat_block(5), flat_block(5), flat_block(7));
  auto r = run(tiler() + " validate " + path, dir.path());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.out.find("a sample differs from child"), std::string::npos) << r.out;
}

TEST(ValidateCli, DetectsUnsaturatedErrors) {
  TempDir dir;
  MBlock west = flat_block(5);
  west.vertex_error.back() = 9;  // a leaf-level vertex larger than its ancestors
  const auto path = write_package(dir, west, flat_block(5), flat_block(5));
  auto r = run(tiler() + " validate " + path, dir.path());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.out.find("not saturated"), std::string::npos) << r.out;
}

TEST(ValidateCli, ReportsCorruptTilesWithTheirIdAndSpecSection) {
  TempDir dir;
  auto blob = tileformat::encode_mblock(flat_block(5));
  blob.resize(blob.size() - 3);
  const auto path = write_package(dir, flat_block(5), flat_block(5), flat_block(5), blob);
  auto r = run(tiler() + " validate " + path, dir.path());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.out.find("tile 1/0/0:"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("tileformat §4"), std::string::npos) << r.out;
  auto e =
      run(tiler() + " extract " + path + " --zoom 1 -o " + (dir / "x.tif").string(), dir.path());
  EXPECT_EQ(e.exit_code, 1);
  EXPECT_NE(e.err.find("tile 1/0/0"), std::string::npos) << e.err;
  EXPECT_FALSE(fs::exists(dir / "x.tif"));
}
