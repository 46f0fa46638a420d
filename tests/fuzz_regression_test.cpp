// Replays every saved fuzz input (tests/data/fuzz/<target>/) through the
// fuzz targets' entries: each must be rejected cleanly or decode consistently
// (the entries abort otherwise, and CI runs this under ASan + UBSan).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <vector>

#include "fuzz/fuzz_entries.hpp"
#include "test_paths.hpp"
#include "test_support.hpp"

namespace fs = std::filesystem;

namespace {

std::vector<std::vector<uint8_t>> inputs(const std::string& target) {
  std::vector<std::vector<uint8_t>> out;
  const fs::path dir = fs::path(globe_test::paths::test_data_dir()) / "fuzz" / target;
  for (const auto& e : fs::directory_iterator(dir)) {
    std::ifstream in(e.path(), std::ios::binary);
    out.emplace_back(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  return out;
}

}  // namespace

TEST(FuzzRegression, MBlockInputs) {
  const auto all = inputs("mblock");
  EXPECT_FALSE(all.empty());
  for (const auto& bytes : all)
    globe_fuzz::mblock(bytes);
}

TEST(FuzzRegression, ImageTileInputs) {
  const auto all = inputs("image_tile");
  EXPECT_FALSE(all.empty());
  for (const auto& bytes : all)
    globe_fuzz::image_tile(bytes);
}

TEST(FuzzRegression, LineTileInputs) {
  const auto all = inputs("line_tile");
  EXPECT_FALSE(all.empty());
  for (const auto& bytes : all)
    globe_fuzz::line_tile(bytes);
}

TEST(FuzzRegression, PointTileInputs) {
  const auto all = inputs("point_tile");
  EXPECT_FALSE(all.empty());
  for (const auto& bytes : all)
    globe_fuzz::point_tile(bytes);
}

TEST(FuzzRegression, AreaTileInputs) {
  const auto all = inputs("area_tile");
  EXPECT_FALSE(all.empty());
  for (const auto& bytes : all)
    globe_fuzz::area_tile(bytes);
}

TEST(FuzzRegression, AnalysisBlockInputs) {
  const auto all = inputs("analysis_block");
  EXPECT_FALSE(all.empty());
  for (const auto& bytes : all)
    globe_fuzz::analysis_block(bytes);
}

TEST(FuzzRegression, UrlRouteInputs) {
  const auto all = inputs("url_route");
  EXPECT_FALSE(all.empty());
  for (const auto& bytes : all)
    globe_fuzz::url_route(bytes);
}

TEST(FuzzRegression, PackageInputs) {
  globe_test::TempDir dir;
  const auto all = inputs("package");
  EXPECT_FALSE(all.empty());
  for (const auto& bytes : all)
    globe_fuzz::package(bytes, (dir / "p.mbtiles").string());
}
