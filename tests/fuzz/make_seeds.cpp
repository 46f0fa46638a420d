// Writes the fuzzers' seed corpus: valid blobs of every tile kind and small
// valid packages, one file each, under OUT/<target>/.
// Usage: make_fuzz_seeds OUT
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "../golden_block.hpp"
#include "tileformat/analysis_block.hpp"
#include "tileformat/area_tile.hpp"
#include "tileformat/kpatch.hpp"
#include "tileformat/line_clusters.hpp"
#include "tileformat/line_tile.hpp"
#include "tileformat/mblock.hpp"
#include "tileformat/metadata.hpp"
#include "tileformat/package.hpp"
#include "tileformat/point_tile.hpp"

namespace fs = std::filesystem;
using Bytes = std::vector<uint8_t>;

namespace {

void save(const fs::path& dir, const std::string& name, const Bytes& bytes) {
  fs::create_directories(dir);
  std::ofstream(dir / name, std::ios::binary)
      .write(reinterpret_cast<const char*>(bytes.data()),
             static_cast<std::streamsize>(bytes.size()));
}

std::vector<Bytes> mblocks() {
  tileformat::MBlock full = golden_block();
  full.valid.clear();
  tileformat::MBlock big;
  big.size = 65;
  big.lattice = 16;
  big.step = 0.01;
  for (int i = 0; i < 65 * 65; ++i)
    big.q.push_back(100000 + (i * 7919) % 4000 - (i / 65) * 3);
  big.vertex_error.assign(tileformat::kpatch_vertex_count(tileformat::kpatch_depth(64, 16)), 5);
  return {tileformat::encode_mblock(golden_block()),
          tileformat::encode_mblock(full, 9, tileformat::HeightCoding::kBytePlanes),
          tileformat::encode_mblock(big)};
}

std::vector<Bytes> line_tiles() {
  tileformat::LineTile t;
  t.extent = 4096;
  t.grid = 8;
  t.reach = 16;
  t.feature_ids = {3, 9};
  t.vertices = {{10, 10}, {2000, 300}, {4000, 4000}, {-50, 2000}, {1000, 1000}};
  t.runs = {{0, 0, 0, 3}, {1, 2, 3, 2}};
  t.points = {{1, 1, {512, 512}}};
  tileformat::build_cluster_grid(t);
  tileformat::LineTile empty;
  empty.extent = 4096;
  empty.grid = 1;
  tileformat::build_cluster_grid(empty);
  return {tileformat::encode_line_tile(t), tileformat::encode_line_tile(empty)};
}

std::vector<Bytes> point_tiles() {
  tileformat::PointTile t;
  t.grid = 4;
  t.reach = 200;
  t.fields = 2;
  t.places = {{2, 1, {10, 4000}}, {7, 3, {2048, 2048}}, {100, 1, {4096, 0}}};
  t.values = {1.5f, 0, 3, 4e6f, 0.25f, 7};
  tileformat::build_point_grid(t);
  tileformat::PointTile empty;
  empty.grid = 1;
  empty.fields = 1;
  tileformat::build_point_grid(empty);
  return {tileformat::encode_point_tile(t), tileformat::encode_point_tile(empty)};
}

std::vector<Bytes> area_tiles() {
  tileformat::AreaTile t;  // a square with a square hole, and a triangle past the edge
  t.buffer = 64;
  t.feature_ids = {3, 9};
  t.polygons = {{0, 1, 0, 2}, {1, 0, 2, 1}};
  t.ring_sizes = {4, 4, 3};
  t.vertices = {{0, 0},       {4000, 0},    {4000, 4000}, {0, 4000},   {1000, 1000}, {1000, 3000},
                {3000, 3000}, {3000, 1000}, {4100, -50},  {4150, 200}, {3900, 100}};
  tileformat::AreaTile empty;
  return {tileformat::encode_area_tile(t), tileformat::encode_area_tile(empty)};
}

std::vector<Bytes> image_headers() {
  Bytes png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n', 0, 0, 0, 13, 'I', 'H', 'D', 'R', 0,
               0,    1,   0,   0,   0,    1,    0,    8,    6, 0, 0, 0,  1,   2,   3,   4};
  Bytes jpeg = {0xFF, 0xD8, 0xFF, 0xE0, 0, 4,    'J', 'F', 0xFF, 0xC0, 0,    11,   8, 1,
                0,    1,    0,    3,    1, 0x22, 0,   2,   0x11, 1,    0xFF, 0xDA, 0, 2};
  Bytes vp8l = {'R', 'I', 'F', 'F', 22, 0,    0,    0,    'W',  'E',  'B', 'P', 'V', 'P', '8',
                'L', 10,  0,   0,   0,  0x2f, 0xff, 0xc0, 0x3f, 0x10, 0,   0,   0,   0,   0};
  Bytes vp8x = {'R', 'I', 'F', 'F', 22, 0,    0, 0, 'W', 'E',  'B', 'P', 'V',  'P', '8',
                'X', 10,  0,   0,   0,  0x10, 0, 0, 0,   0xff, 0,   0,   0xff, 0,   0};
  return {png, jpeg, vp8l, vp8x};
}

// A block of every coding: slope as residuals, flow directions packed, and
// upstream areas predicted along them (a 5 x 5 block draining east).
std::vector<Bytes> analysis_blocks() {
  tileformat::AnalysisBlock b;
  b.size = 5;
  b.layers = {tileformat::AnalysisLayer::kSlope, tileformat::AnalysisLayer::kFlowDirection,
              tileformat::AnalysisLayer::kFlowAccumulation};
  std::vector<uint16_t> slope, code, area;
  for (int y = 0; y < 5; ++y)
    for (int x = 0; x < 5; ++x) {
      slope.push_back(uint16_t(100 * x + 7 * y));
      code.push_back(y == 4 ? tileformat::kNoValue : x == 4 ? 0 : 3);
      area.push_back(y == 4 ? tileformat::kNoValue : uint16_t(20000 + 1000 * x + y % 2));
    }
  b.values = {slope, code, area};
  tileformat::AnalysisBlock flat = b;
  flat.layers = {tileformat::AnalysisLayer::kSkyview};
  flat.values = {slope};
  return {tileformat::encode_analysis_block(b), tileformat::encode_analysis_block(flat)};
}

Bytes package(const fs::path& scratch, const char* format, const std::vector<Bytes>& blobs) {
  const std::string path = (scratch / "seed.mbtiles").string();
  fs::remove(path);
  {
    tileformat::PackageWriter w(path, tileformat::IfExists::kOverwrite);
    w.set_metadata("name", "seed");
    w.set_metadata("format", format);
    w.set_metadata("minzoom", "0");
    w.set_metadata("maxzoom", "1");
    uint32_t x = 0;
    for (const Bytes& b : blobs)
      w.put_tile({1, x++, 1}, b);
    w.commit();
  }
  std::ifstream in(path, std::ios::binary);
  Bytes bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  fs::remove(path);
  return bytes;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: make_fuzz_seeds OUT\n");
    return 2;
  }
  const fs::path out = argv[1];
  const auto m = mblocks(), l = line_tiles(), i = image_headers(), p = point_tiles(),
             a = analysis_blocks(), r = area_tiles();
  for (size_t k = 0; k < m.size(); ++k)
    save(out / "mblock", "seed" + std::to_string(k), m[k]);
  for (size_t k = 0; k < l.size(); ++k)
    save(out / "line_tile", "seed" + std::to_string(k), l[k]);
  for (size_t k = 0; k < i.size(); ++k)
    save(out / "image_tile", "seed" + std::to_string(k), i[k]);
  for (size_t k = 0; k < p.size(); ++k)
    save(out / "point_tile", "seed" + std::to_string(k), p[k]);
  for (size_t k = 0; k < a.size(); ++k)
    save(out / "analysis_block", "seed" + std::to_string(k), a[k]);
  for (size_t k = 0; k < r.size(); ++k)
    save(out / "area_tile", "seed" + std::to_string(k), r[k]);
  fs::create_directories(out / "package");
  save(out / "package", "seed0", package(out, tileformat::kMBlockFormat, {m[0], m[1]}));
  save(out / "package", "seed1", package(out, tileformat::kLineClustersFormat, l));
  save(out / "package", "seed2", package(out, "png", {i[0]}));
  save(out / "package", "seed3", package(out, tileformat::kPointsFormat, p));
  save(out / "package", "seed4", package(out, tileformat::kAnalysisFormat, a));
  save(out / "package", "seed5", package(out, tileformat::kAreasFormat, r));
  return 0;
}
