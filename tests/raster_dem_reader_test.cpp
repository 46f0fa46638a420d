// Raster-DEM tiles as terrain blocks (viewer/data/raster_dem_reader.hpp,
// block_synthesizer.hpp) against a brute force written here: an in-memory
// fetcher serves Terrarium / Terrain-RGB PNGs of an analytic field (a hill,
// a ramp and ripples over the whole web-mercator world, zooms 0..4), encoded
// with libpng directly (not through the project's png_codec). Checked: every
// block sample is the mean of the field's four pixel centres around its
// corner (poles and missing tiles clamped to the nearest pixel centre);
// neighbours share their edge samples in q, the antimeridian included;
// edge vertices carry the same error in both blocks and errors are
// saturated, across block edges too; Terrain-RGB gives the same heights
// within 0.1 m; fetcher failures become PackageErrors naming the URL; the
// metadata is a terrain package's; the same inputs give the same bytes from
// any number of threads.
#include <gtest/gtest.h>
#include <png.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <map>
#include <mutex>
#include <numbers>
#include <set>
#include <stdexcept>
#include <thread>

#include "data/block_synthesizer.hpp"
#include "data/raster_dem_reader.hpp"
#include "tileformat/error.hpp"
#include "tileformat/kpatch.hpp"
#include "tileformat/mblock.hpp"
#include "tileformat/metadata.hpp"
#include "tileformat/package_kinds.hpp"

namespace {

using globe::viewer::BlockSynthesizer;
using globe::viewer::DemEncoding;
using globe::viewer::RasterDemReader;
using globe::viewer::RasterTileFetcher;
using tileformat::KPatchLayout;
using tileformat::MBlock;
using tileformat::TileId;

constexpr int kPx = 256;
constexpr int kMaxZoom = 4;
constexpr int kBlock = kPx + 1;

// The field at web-mercator (u, v) in 0..1 from the north-west corner:
// -3300 .. 5800 m, rough enough for non-zero errors at every zoom.
double field(double u, double v) {
  const double pi = std::numbers::pi;
  const double hill = 2500 * std::exp(-((u - 0.55) * (u - 0.55) + (v - 0.4) * (v - 0.4)) / 0.002);
  return hill - 6000 * (v - 0.5) + 300 * std::sin(40 * pi * u) * std::cos(30 * pi * v);
}

// Global pixel (px, py) of zoom z: its centre's height.
double pixel_field(int z, int64_t px, int64_t py) {
  const double n = double(kPx) * double(int64_t{1} << z);
  return field((double(px) + 0.5) / n, (double(py) + 0.5) / n);
}

// The pixel codes, as the formulas of the two encodings (independent of the
// reader's decoder).
void encode_pixel(DemEncoding e, double h, uint8_t* rgb) {
  const int64_t t = e == DemEncoding::kTerrarium ? std::llround((h + 32768) * 256)
                                                 : std::llround((h + 10000) * 10);
  rgb[0] = uint8_t(t >> 16);
  rgb[1] = uint8_t(t >> 8);
  rgb[2] = uint8_t(t);
}

std::vector<uint8_t> png_rgb(const std::vector<uint8_t>& rgb, int w, int h) {
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png_create_info_struct(png);
  std::vector<uint8_t> out;
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    throw std::runtime_error("test PNG encoder failed");
  }
  png_set_write_fn(
      png, &out,
      [](png_structp p, png_bytep data, png_size_t n) {
        auto* o = static_cast<std::vector<uint8_t>*>(png_get_io_ptr(p));
        o->insert(o->end(), data, data + n);
      },
      nullptr);
  png_set_IHDR(png, info, uint32_t(w), uint32_t(h), 8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_set_compression_level(png, 0);  // stored: the test's time goes to the code under test
  png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_FILTER_NONE);
  png_write_info(png, info);
  for (int y = 0; y < h; ++y)
    png_write_row(png, const_cast<png_bytep>(&rgb[size_t(y) * w * 3]));
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  return out;
}

// The encoded tiles of the field, made once per test run.
const std::vector<uint8_t>& source_png(DemEncoding e, TileId id) {
  static std::mutex m;
  static std::map<std::pair<int, TileId>, std::vector<uint8_t>> made;
  std::lock_guard lock(m);
  auto [it, fresh] = made.try_emplace({int(e), id});
  if (fresh) {
    std::vector<uint8_t> rgb(size_t(kPx) * kPx * 3);
    for (int j = 0; j < kPx; ++j)
      for (int i = 0; i < kPx; ++i)
        encode_pixel(e, pixel_field(id.z, int64_t{id.x} * kPx + i, int64_t{id.y} * kPx + j),
                     &rgb[(size_t(j) * kPx + i) * 3]);
    it->second = png_rgb(rgb, kPx, kPx);
  }
  return it->second;
}

class FakeFetcher final : public RasterTileFetcher {
 public:
  explicit FakeFetcher(DemEncoding e,
                       std::array<double, 4> bounds = {-180, -85.0511287798, 180, 85.0511287798})
      : encoding_(e), bounds_(bounds) {}
  std::optional<std::vector<uint8_t>> fetch(TileId id) override {
    ++fetches;
    if (failing.count(id)) throw tileformat::PackageError(url(id) + ": HTTP 503");
    if (broken.count(id)) throw std::runtime_error("connection reset");
    if (missing.count(id) || id.z > kMaxZoom) return std::nullopt;
    return source_png(encoding_, id);
  }
  void prefetch(std::span<const TileId> ids) override {
    std::lock_guard lock(mutex_);
    prefetched.emplace_back(ids.begin(), ids.end());
  }
  int min_zoom() const override { return 0; }
  int max_zoom() const override { return kMaxZoom; }
  std::array<double, 4> bounds() const override { return bounds_; }
  const std::string& name() const override { return name_; }
  std::string url(TileId id) const {
    return "https://dem.test/" + std::to_string(id.z) + "/" + std::to_string(id.x) + "/" +
           std::to_string(id.y) + ".png";
  }

  std::set<TileId> missing, failing, broken;
  std::atomic<int> fetches{0};
  std::vector<std::vector<TileId>> prefetched;

 private:
  DemEncoding encoding_;
  std::array<double, 4> bounds_;
  std::string name_ = "https://dem.test/{z}/{x}/{y}.png";
  std::mutex mutex_;
};

// The brute force: sample (i, j) of block `id` is the mean of the four pixel
// centres around its corner, pixel indices clamped to the world's rows and,
// where `west_missing`, to the block's own first column; columns wrap.
double expected_sample(TileId id, int i, int j, bool west_missing = false) {
  const int64_t width = int64_t{kPx} << id.z;
  double sum = 0;
  for (int64_t py : {int64_t{id.y} * kPx + j - 1, int64_t{id.y} * kPx + j})
    for (int64_t px : {int64_t{id.x} * kPx + i - 1, int64_t{id.x} * kPx + i}) {
      py = std::clamp<int64_t>(py, 0, width - 1);
      if (west_missing) px = std::max<int64_t>(px, int64_t{id.x} * kPx);
      sum += pixel_field(id.z, (px + width) % width, py);
    }
  return sum / 4;
}

MBlock block_of(RasterDemReader& r, TileId id) {
  auto blob = r.tile(id);
  if (!blob) throw std::runtime_error("no block at " + id.str());
  return tileformat::decode_mblock(*blob);
}

TileId wrapped(TileId id, int dx, int dy) {
  const int64_t n = int64_t{1} << id.z;
  return {id.z, uint32_t((int64_t{id.x} + dx + n) % n), uint32_t(int64_t{id.y} + dy)};
}

TEST(RasterDem, PixelFormulas) {
  using globe::viewer::dem_pixel_height;
  EXPECT_EQ(dem_pixel_height(DemEncoding::kTerrarium, 128, 0, 0, 255), 0.0);
  EXPECT_EQ(dem_pixel_height(DemEncoding::kTerrarium, 0, 0, 0, 255), -32768.0);
  EXPECT_EQ(dem_pixel_height(DemEncoding::kTerrarium, 128, 1, 128, 255), 1.5);
  EXPECT_NEAR(dem_pixel_height(DemEncoding::kTerrainRgb, 1, 134, 160, 255), 0.0, 1e-9);
  EXPECT_NEAR(dem_pixel_height(DemEncoding::kTerrainRgb, 0, 0, 0, 255), -10000.0, 1e-9);
  EXPECT_TRUE(std::isnan(dem_pixel_height(DemEncoding::kTerrarium, 128, 0, 0, 0)));
  // Heights of -11000..9000 m stay far inside the format's quanta.
  for (DemEncoding e : {DemEncoding::kTerrarium, DemEncoding::kTerrainRgb})
    EXPECT_LT(11000 / globe::viewer::dem_height_step(e), tileformat::kMaxQuantum / 100);
}

// (a) Every sample, on blocks of every zoom, at the poles, across the
// antimeridian and inside.
TEST(RasterDem, SamplesAreThePixelCornersOfTheField) {
  FakeFetcher f(DemEncoding::kTerrarium);
  RasterDemReader r(f, DemEncoding::kTerrarium);
  const double step = globe::viewer::dem_height_step(DemEncoding::kTerrarium);
  EXPECT_EQ(step, 1.0 / 64);
  // Pixel rounding (1/512 m), the block's rounding (step / 2), float.
  const double tol = 1.0 / 512 + step / 2 + 2e-3;
  for (TileId id : {TileId{0, 0, 0}, TileId{1, 1, 0}, TileId{2, 0, 3}, TileId{3, 7, 3},
                    TileId{4, 8, 6}, TileId{4, 15, 15}}) {
    const MBlock b = block_of(r, id);
    ASSERT_EQ(b.size, kBlock);
    EXPECT_EQ(b.step, step);
    EXPECT_TRUE(b.valid.empty()) << id.str();
    double worst = 0;
    for (int j = 0; j < kBlock; ++j)
      for (int i = 0; i < kBlock; ++i)
        worst = std::max(worst, std::abs(b.height(i, j) - expected_sample(id, i, j)));
    EXPECT_LE(worst, tol) << id.str();
    // samples() is what the blocks quantize.
    const auto s = r.samples(id);
    ASSERT_TRUE(s);
    for (int k : {0, 256, 33000, kBlock * kBlock - 1})
      EXPECT_EQ(b.q[size_t(k)], std::lround((*s)[size_t(k)] / step)) << id.str() << " " << k;
  }
}

// (b) Shared edges: the east and south neighbours, the antimeridian (the
// last column's east is column 0; at zoom 0 the tile is its own neighbour).
TEST(RasterDem, NeighboursShareTheirEdgeSamples) {
  FakeFetcher f(DemEncoding::kTerrarium);
  RasterDemReader r(f, DemEncoding::kTerrarium);
  auto check_east = [&](TileId a, TileId b) {
    const MBlock ma = block_of(r, a), mb = block_of(r, b);
    for (int j = 0; j < kBlock; ++j)
      ASSERT_EQ(ma.q[size_t(j) * kBlock + kPx], mb.q[size_t(j) * kBlock]) << a.str() << " " << j;
  };
  auto check_south = [&](TileId a, TileId b) {
    const MBlock ma = block_of(r, a), mb = block_of(r, b);
    for (int i = 0; i < kBlock; ++i)
      ASSERT_EQ(ma.q[size_t(kPx) * kBlock + i], mb.q[size_t(i)]) << a.str() << " " << i;
  };
  check_east({0, 0, 0}, {0, 0, 0});
  check_east({2, 3, 1}, {2, 0, 1});
  check_east({4, 15, 9}, {4, 0, 9});
  check_east({3, 2, 5}, {3, 3, 5});
  check_south({3, 2, 5}, {3, 2, 6});
  check_south({4, 15, 0}, {4, 15, 1});
}

// The error tree's vertices: depth and position of every split vertex.
struct VertexRef {
  int depth;
  tileformat::Point p;
};
std::vector<VertexRef> vertices(const KPatchLayout& l) {
  std::vector<VertexRef> out;
  for (int d = 0; d <= l.depth(); ++d)
    for (size_t v = l.vertex_offset(d); v < l.vertex_offset(d + 1); ++v)
      out.push_back({d, l.vertex_position(v)});
  return out;
}

// (c) Edge vertices read the same neighbourhood from both blocks: the same
// error in both. And e(v) >= e(child) for every child in the block or its
// 8 neighbours (children of an edge midpoint lie on both sides).
TEST(RasterDem, EdgeVertexErrorsAgreeAndAreSaturated) {
  FakeFetcher f(DemEncoding::kTerrarium);
  RasterDemReader r(f, DemEncoding::kTerrarium);
  for (TileId centre : {TileId{3, 7, 2}, TileId{2, 0, 0}, TileId{4, 8, 6}}) {
    std::map<std::pair<int, int>, MBlock> around;  // by (dx, dy)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx)
        if (int64_t{centre.y} + dy >= 0 && int64_t{centre.y} + dy < (int64_t{1} << centre.z))
          around.emplace(std::pair{dx, dy}, block_of(r, wrapped(centre, dx, dy)));
    const KPatchLayout own(kPx, 16, centre.diagonal());
    const MBlock& b = around.at({0, 0});
    const auto verts = vertices(own);
    ASSERT_EQ(b.vertex_error.size(), verts.size());
    uint32_t largest = 0;
    for (size_t v = 0; v < verts.size(); ++v) {
      largest = std::max(largest, b.vertex_error[v]);
      const auto [d, p] = verts[v];
      // The same vertex seen from the neighbour across the edge it lies on.
      for (auto [dx, dy] : {std::pair{-1, 0}, std::pair{1, 0}, std::pair{0, -1}, std::pair{0, 1}}) {
        const bool on_edge = (dx == -1 && p.x == 0) || (dx == 1 && p.x == kPx) ||
                             (dy == -1 && p.y == 0) || (dy == 1 && p.y == kPx);
        if (!on_edge || !around.count({dx, dy})) continue;
        const TileId n = wrapped(centre, dx, dy);
        const KPatchLayout other(kPx, 16, n.diagonal());
        const size_t w = other.vertex_at(d, {p.x - dx * kPx, p.y - dy * kPx});
        EXPECT_EQ(b.vertex_error[v], around.at({dx, dy}).vertex_error[w])
            << centre.str() << " vertex " << v << " (" << p.x << "," << p.y << ") vs " << n.str();
      }
    }
    EXPECT_GT(largest, 0u) << centre.str();  // not a vacuous check
    // Saturation over the 4-8 hierarchy inside the block and across its edges.
    const int levels = own.depth() / 2;
    auto error_of_cell_centre = [&](const tileformat::Cell& c) -> std::optional<uint32_t> {
      const tileformat::BlockCell bc = tileformat::locate_cell(c);
      const auto it = around.find({bc.dx, bc.dy});
      if (it == around.end()) return std::nullopt;
      return it->second.vertex_error[own.cell_vertex(c.m, bc.cell.cx, bc.cell.cy)];
    };
    for (int m = 0; m < levels; ++m) {
      const int cells = 1 << m;
      for (int cy = 0; cy < cells; ++cy)
        for (int cx = 0; cx < cells; ++cx)
          for (size_t k : own.centre_children(m, cx, cy))
            EXPECT_GE(b.vertex_error[own.cell_vertex(m, cx, cy)], b.vertex_error[k]);
      for (int row = 0; row <= cells; ++row)
        for (int cx = 0; cx < cells; ++cx)
          for (const auto& c : KPatchLayout::hedge_children(m, row, cx))
            if (auto e = error_of_cell_centre(c)) {
              EXPECT_GE(b.vertex_error[own.hedge_vertex(m, row, cx)], *e) << centre.str();
            }
      for (int cy = 0; cy < cells; ++cy)
        for (int col = 0; col <= cells; ++col)
          for (const auto& c : KPatchLayout::vedge_children(m, cy, col))
            if (auto e = error_of_cell_centre(c)) {
              EXPECT_GE(b.vertex_error[own.vedge_vertex(m, cy, col)], *e) << centre.str();
            }
    }
  }
}

// (d) The same field as Terrain-RGB: heights within 0.1 m of the brute
// force (pixel codes of 0.1 m, blocks on a 0.1 m step).
TEST(RasterDem, TerrainRgbGivesTheSameHeights) {
  FakeFetcher f(DemEncoding::kTerrainRgb);
  RasterDemReader r(f, DemEncoding::kTerrainRgb);
  EXPECT_EQ(tileformat::read_terrain_metadata(r.metadata()).height_step, 0.1);
  FakeFetcher ft(DemEncoding::kTerrarium);
  RasterDemReader rt(ft, DemEncoding::kTerrarium);
  for (TileId id : {TileId{1, 0, 1}, TileId{4, 9, 6}}) {
    const MBlock b = block_of(r, id), bt = block_of(rt, id);
    EXPECT_EQ(b.step, 0.1);
    double worst = 0, worst_t = 0;
    for (int j = 0; j < kBlock; ++j)
      for (int i = 0; i < kBlock; ++i) {
        worst = std::max(worst, std::abs(b.height(i, j) - expected_sample(id, i, j)));
        worst_t = std::max(worst_t, std::abs(b.height(i, j) - bt.height(i, j)));
      }
    EXPECT_LE(worst, 0.1 + 1e-3) << id.str();
    EXPECT_LE(worst_t, 0.1 + 0.01) << id.str();
  }
}

// (e) A missing tile is no block; a failing one is a PackageError naming the
// URL, also when it is a neighbour the block's edges need; a missing
// neighbour clamps the edge to the block's own pixels.
TEST(RasterDem, MissingAndFailingTiles) {
  FakeFetcher f(DemEncoding::kTerrarium);
  f.missing = {{3, 4, 4}};
  f.failing = {{3, 1, 1}};
  f.broken = {{3, 0, 7}};
  RasterDemReader r(f, DemEncoding::kTerrarium);
  EXPECT_TRUE(r.has_tile({3, 4, 4}));
  EXPECT_FALSE(r.tile({3, 4, 4}).has_value());
  EXPECT_FALSE(r.has_tile({3, 4, 4}));                    // answered absent
  for (TileId id : {TileId{3, 1, 1}, TileId{3, 2, 2}}) {  // the tile, then a neighbour's block
    try {
      r.tile(id);
      ADD_FAILURE() << id.str() << " did not throw";
    } catch (const tileformat::PackageError& e) {
      EXPECT_NE(std::string(e.what()).find("https://dem.test/3/1/1.png"), std::string::npos)
          << e.what();
    }
  }
  try {
    r.tile({3, 0, 7});
    ADD_FAILURE() << "3/0/7 did not throw";
  } catch (const tileformat::PackageError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("https://dem.test/{z}/{x}/{y}.png"), std::string::npos) << what;
    EXPECT_NE(what.find("3/0/7"), std::string::npos) << what;
    EXPECT_NE(what.find("connection reset"), std::string::npos) << what;
  }
  // The block east of the missing tile: its west edge from its own pixels
  // (the corners also see the diagonal tiles, which are there: left out).
  const TileId east{3, 5, 4};
  const MBlock b = block_of(r, east);
  const double tol = 1.0 / 512 + 1.0 / 128 + 2e-3;
  for (int j = 1; j < kPx; ++j)
    for (int i : {0, 1, 128})
      EXPECT_NEAR(b.height(i, j), expected_sample(east, i, j, true), tol) << i << "," << j;
  // The failing tile is asked again (not remembered as absent).
  const int before = f.fetches;
  EXPECT_THROW(r.tile({3, 1, 1}), tileformat::PackageError);
  EXPECT_GT(f.fetches, before);
}

TEST(RasterDem, MetadataIsATerrainPackages) {
  FakeFetcher f(DemEncoding::kTerrarium, {0, 0, 90, 45});
  RasterDemReader r(f, DemEncoding::kTerrarium);
  const tileformat::TerrainMetadata m = tileformat::read_terrain_metadata(r.metadata());
  EXPECT_EQ(m.common.format, tileformat::kMBlockFormat);
  EXPECT_EQ(m.common.tiling.scheme, tileformat::Scheme::kWebMercator);
  EXPECT_EQ(m.block_size, 257);
  EXPECT_EQ(m.lattice, 16);
  EXPECT_EQ(m.height_step, 1.0 / 64);
  EXPECT_EQ(m.common.min_zoom, 0);
  EXPECT_EQ(m.common.max_zoom, kMaxZoom);
  EXPECT_EQ(r.meta("bounds").value_or(""), "0,0,90,45");
  EXPECT_EQ(r.path(), f.name());
  // The keys a package built by globe-tiler terrain has.
  for (const char* key : {"name",
                          "format",
                          "bounds",
                          "center",
                          "minzoom",
                          "maxzoom",
                          "type",
                          "version",
                          "description",
                          "globe:scheme",
                          "globe:crs",
                          "globe:origin",
                          "globe:root_size",
                          "globe:roots",
                          "globe:format_version",
                          "globe:block_size",
                          "globe:kpatch_lattice",
                          "globe:height_step",
                          "globe:fill_height",
                          "globe:resampling",
                          "globe:generator",
                          "globe:command_line",
                          "globe:inputs"})
    EXPECT_TRUE(r.meta(key).has_value()) << key;
  // Tiles in bounds: lon 0..90, lat 0..45 is tile (2, 2, 1) at zoom 2.
  EXPECT_EQ(r.tile_ids(2), (std::vector<TileId>{{2, 2, 1}}));
  EXPECT_TRUE(r.has_tile({2, 2, 1}));
  EXPECT_FALSE(r.has_tile({2, 3, 1}));
  EXPECT_FALSE(r.has_tile({5, 16, 8}));  // beyond the source's zooms
  EXPECT_TRUE(r.tile_ids(5).empty());
  // A block at the bounds' edge: neighbours outside them are not fetched,
  // the edge is clamped, and the block is made.
  f.fetches = 0;
  EXPECT_TRUE(r.tile({2, 2, 1}).has_value());
  EXPECT_EQ(f.fetches, 1);
  FakeFetcher world(DemEncoding::kTerrarium);
  RasterDemReader rw(world, DemEncoding::kTerrarium);
  EXPECT_EQ(rw.tile_ids(4).size(), 256u);
  const std::vector<TileId> z3 = rw.tile_ids(3);
  EXPECT_EQ(z3.size(), 64u);
  EXPECT_TRUE(std::is_sorted(z3.begin(), z3.end(), [](TileId a, TileId b) {
    return std::pair(a.y, a.x) < std::pair(b.y, b.x);
  }));
}

TEST(RasterDem, PrefetchAsksForTheNeighbourhoodsWantedFirst) {
  FakeFetcher f(DemEncoding::kTerrarium);
  RasterDemReader r(f, DemEncoding::kTerrarium);
  const std::vector<TileId> wanted = {{2, 1, 1}, {2, 0, 0}};
  r.prefetch(wanted);
  ASSERT_EQ(f.prefetched.size(), 1u);
  const std::vector<TileId>& asked = f.prefetched[0];
  EXPECT_EQ(asked[0], wanted[0]);
  EXPECT_EQ(asked[1], wanted[1]);
  // 9 around (2,1,1); around (2,0,0) the row beyond the pole is not there
  // and its west wraps to column 3: 2 more, once each.
  const std::set<TileId> unique(asked.begin(), asked.end());
  EXPECT_EQ(unique.size(), asked.size());
  EXPECT_EQ(asked.size(), 9u + 2u);
  EXPECT_TRUE(unique.count({2, 3, 0}) && unique.count({2, 3, 1}));
}

// Same inputs, same bytes: a second reader, and four threads at once.
TEST(RasterDem, BlobsAreDeterministicAcrossThreads) {
  FakeFetcher f(DemEncoding::kTerrarium);
  RasterDemReader serial(f, DemEncoding::kTerrarium);
  std::vector<TileId> ids;
  for (uint32_t x = 0; x < 4; ++x)
    ids.push_back({3, x * 2, 3});
  std::vector<std::vector<uint8_t>> want;
  for (TileId id : ids)
    want.push_back(*serial.tile(id));
  RasterDemReader shared(f, DemEncoding::kTerrarium);
  std::vector<std::vector<std::vector<uint8_t>>> got(4);
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t)
    threads.emplace_back([&, t] {
      for (size_t k = 0; k < ids.size(); ++k)
        got[size_t(t)].push_back(*shared.tile(ids[(k + size_t(t)) % ids.size()]));
    });
  for (auto& th : threads)
    th.join();
  for (size_t t = 0; t < 4; ++t)
    for (size_t k = 0; k < ids.size(); ++k)
      EXPECT_EQ(got[t][k], want[(k + t) % ids.size()]) << t << " " << k;
}

// The synthesizer on its own: holes on a shared edge are masked and filled
// alike in both blocks; each grid is read once while the LRU holds the
// neighbourhoods, and a tiny LRU gives the same bytes.
TEST(BlockSynthesizer, HolesOnSharedEdgesAndTheCache) {
  constexpr int kSize = 33;
  const double step = 0.25;
  std::atomic<int> reads{0};
  auto grid = [&](TileId id) -> std::optional<std::vector<float>> {
    ++reads;
    if (id == TileId{2, 3, 3}) return std::nullopt;
    std::vector<float> g(size_t(kSize) * kSize);
    const double n = double(kSize - 1) * 4;
    for (int j = 0; j < kSize; ++j)
      for (int i = 0; i < kSize; ++i) {
        const double u = (id.x * (kSize - 1) + i) / n, v = (id.y * (kSize - 1) + j) / n;
        // A hole across the edge between columns 1 and 2 of row 1.
        const bool hole = std::abs(u - 0.5) < 0.05 && v > 0.3 && v < 0.45;
        g[size_t(j) * kSize + i] = hole ? NAN : float(field(std::fmod(u, 1.0), v));
      }
    return g;
  };
  BlockSynthesizer big(kSize, 16, step, grid, 64);
  std::map<TileId, std::vector<uint8_t>> blobs;
  for (uint32_t y = 0; y < 4; ++y)
    for (uint32_t x = 0; x < 4; ++x)
      if (auto b = big.blob({2, x, y})) blobs[{2, x, y}] = *b;
  EXPECT_EQ(blobs.size(), 15u);
  EXPECT_EQ(reads, 16);  // each tile's grid once
  const MBlock a = tileformat::decode_mblock(blobs.at({2, 1, 1}));
  const MBlock b = tileformat::decode_mblock(blobs.at({2, 2, 1}));
  ASSERT_FALSE(a.valid.empty());
  ASSERT_FALSE(b.valid.empty());
  int holes = 0;
  for (int j = 0; j < kSize; ++j) {
    const size_t ka = size_t(j) * kSize + kSize - 1, kb = size_t(j) * kSize;
    EXPECT_EQ(a.q[ka], b.q[kb]) << j;
    EXPECT_EQ(a.valid[ka], b.valid[kb]) << j;
    holes += a.valid[ka] == 0;
  }
  EXPECT_GT(holes, 0);
  BlockSynthesizer tiny(kSize, 16, step, grid, 2);
  for (const auto& [id, blob] : blobs)
    EXPECT_EQ(tiny.blob(id), blob) << id.str();
  EXPECT_FALSE(tiny.blob({2, 3, 3}).has_value());
  EXPECT_THROW((void)BlockSynthesizer(34, 16, step, grid, 4), std::invalid_argument);
  EXPECT_THROW((void)BlockSynthesizer(33, 32, step, grid, 4), std::invalid_argument);
}

}  // namespace
