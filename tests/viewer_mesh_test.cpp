// The viewer's mesh contract (docs/viewer.md, design §4) on real sample
// packages and random cameras, checked on the triangles the GPU draws
// (captured by transform feedback):
//  1. conforming: no edge is used by more than two triangles, and no vertex
//     lies inside an edge used by only one (a T-junction or a crack);
//  2. the projected vertical error against the finest data is <= tau pixels.
#include <gtest/gtest.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstring>
#include <map>
#include <numbers>
#include <numeric>
#include <random>
#include <set>
#include <sstream>
#include <unordered_map>

#include "app/terrain_scene.hpp"
#include "platform/headless_context.hpp"
#include "test_support.hpp"
#include "tileformat/mblock.hpp"
#include "tileformat/package.hpp"

namespace {

// Under ASan + UBSan (scripts/sanitize.sh) a third of the cameras: the plain
// build checks every camera's mesh, the sanitized one the viewer's selection
// and capture code on each kind of view (docs/ci.md: CI's time budget).
#ifdef GLOBE_ADDRESS_SANITIZER
constexpr int kCameraDivisor = 3;
#else
constexpr int kCameraDivisor = 1;
#endif

using namespace globe_test;
using namespace globe::viewer;

struct Mesh {
  std::vector<glm::dvec3> verts;  // key units (x, y), metres (z)
  std::vector<uint32_t> tris;
};

// Welds the captured vertices on their key point and height (the vertex
// shader's own integer key), so the checks below need no inverse mapping;
// counts in `cracks` the vertices drawn at two different world positions
// (the contract: a vertex shared by patches or blocks is bit-identical).
Mesh weld(const std::vector<CapturedVertex>& c, const FrameResult& fr, size_t& cracks) {
  Mesh m;
  // Keyed by the bits of the three doubles (equal keys, equal bits: none is
  // a NaN or a negative zero that compares equal to another).
  using Key = std::array<double, 3>;
  struct KeyHash {
    size_t operator()(const Key& k) const {
      uint64_t h = 0;
      for (double d : k) {
        uint64_t b;
        std::memcpy(&b, &d, sizeof b);
        h = (h ^ b) * 0x9E3779B97F4A7C15ull;
      }
      return size_t(h ^ (h >> 29));
    }
  };
  std::unordered_map<Key, uint32_t, KeyHash> index;
  index.reserve(c.size());
  std::vector<std::array<float, 3>> world;
  cracks = 0;
  m.tris.reserve(c.size());
  for (const CapturedVertex& v : c) {
    const Key k{double(fr.view.origin.x + v.key[0]), double(fr.view.origin.y + v.key[1]),
                double(v.height_m)};
    const std::array<float, 3> w{v.world[0], v.world[1], v.world[2]};
    auto [it, added] = index.emplace(k, static_cast<uint32_t>(m.verts.size()));
    if (added) {
      m.verts.push_back({k[0], k[1], k[2]});
      world.push_back(w);
    } else if (std::memcmp(world[it->second].data(), w.data(), sizeof w) != 0) {
      ++cracks;
    }
    m.tris.push_back(it->second);
  }
  return m;
}

// Counts edges used more than twice and T-junctions (vertices strictly
// inside an edge that only one triangle uses). Edges are counted by sorting
// them (an edge a < b as one 64-bit number), lattice points looked up by
// binary search: the same counts as maps, at a fraction of their time.
std::pair<size_t, size_t> conformity_errors(const Mesh& m) {
  std::vector<uint64_t> edges;
  edges.reserve(m.tris.size());
  for (size_t t = 0; t < m.tris.size(); t += 3)
    for (int e = 0; e < 3; ++e) {
      uint32_t a = m.tris[t + e], b = m.tris[t + (e + 1) % 3];
      if (a > b) std::swap(a, b);
      edges.push_back(uint64_t{a} << 32 | b);
    }
  std::sort(edges.begin(), edges.end());
  // Vertices are integer key points, so a vertex inside an edge is one of the
  // lattice points strictly between its ends.
  std::vector<std::pair<int64_t, int64_t>> at;
  at.reserve(m.verts.size());
  for (const glm::dvec3& v : m.verts)
    at.push_back({int64_t(v.x), int64_t(v.y)});
  std::sort(at.begin(), at.end());
  size_t overused = 0, tjunctions = 0;
  for (size_t i = 0, j = 0; i < edges.size(); i = j) {
    while (j < edges.size() && edges[j] == edges[i])
      ++j;
    const size_t n = j - i;
    if (n > 2) ++overused;
    if (n != 1) continue;
    const uint32_t first = uint32_t(edges[i] >> 32), second = uint32_t(edges[i]);
    const int64_t ax = int64_t(m.verts[first].x), ay = int64_t(m.verts[first].y);
    const int64_t dx = int64_t(m.verts[second].x) - ax, dy = int64_t(m.verts[second].y) - ay;
    const int64_t g = std::gcd(std::abs(dx), std::abs(dy));
    for (int64_t t = 1; t < g; ++t)
      if (std::binary_search(at.begin(), at.end(),
                             std::pair<int64_t, int64_t>{ax + t * dx / g, ay + t * dy / g}))
        ++tjunctions;
  }
  return {overused, tjunctions};
}

// The finest zoom's samples by key position.
class FinestData {
 public:
  explicit FinestData(const std::string& path) {
    tileformat::PackageReader r(path);
    zoom_ = std::stoi(*r.meta("maxzoom"));
    r.for_each_tile(
        [&](tileformat::TileId id, std::span<const uint8_t> blob) {
          blocks_.emplace(std::pair{id.x, id.y}, tileformat::decode_mblock(blob));
        },
        zoom_);
    steps_ = blocks_.begin()->second.steps();
    for (const auto& [xy, b] : blocks_) {
      lo_x_ = std::min<int64_t>(lo_x_, int64_t{xy.first} * steps_);
      lo_y_ = std::min<int64_t>(lo_y_, int64_t{xy.second} * steps_);
      hi_x_ = std::max<int64_t>(hi_x_, int64_t{xy.first + 1} * steps_);
      hi_y_ = std::max<int64_t>(hi_y_, int64_t{xy.second + 1} * steps_);
    }
  }
  // Key-unit box holding every finest sample.
  int64_t lo_x_ = INT64_MAX, lo_y_ = INT64_MAX, hi_x_ = INT64_MIN, hi_y_ = INT64_MIN;
  // Height in metres of the finest sample at key (x, y), if valid.
  std::optional<double> at(int64_t x, int64_t y) const {
    auto it = blocks_.find({static_cast<uint32_t>(x / steps_), static_cast<uint32_t>(y / steps_)});
    if (it == blocks_.end()) {
      if (x % steps_ == 0 && x > 0) return at_tile(x, y, x / steps_ - 1, y / steps_);
      if (y % steps_ == 0 && y > 0) return at_tile(x, y, x / steps_, y / steps_ - 1);
      return std::nullopt;
    }
    return at_tile(x, y, x / steps_, y / steps_);
  }

 private:
  std::optional<double> at_tile(int64_t x, int64_t y, int64_t tx, int64_t ty) const {
    auto it = blocks_.find({static_cast<uint32_t>(tx), static_cast<uint32_t>(ty)});
    if (it == blocks_.end()) return std::nullopt;
    const int lx = static_cast<int>(x - tx * steps_), ly = static_cast<int>(y - ty * steps_);
    if (!it->second.is_valid(lx, ly)) return std::nullopt;
    return it->second.height(lx, ly);
  }
  int zoom_ = 0, steps_ = 256;
  std::map<std::pair<uint32_t, uint32_t>, tileformat::MBlock> blocks_;
};

// Largest projected error (pixels) of the mesh against every valid finest sample.
double max_projected_error(const Mesh& m, const FinestData& data, const FrameResult& fr,
                           const WorldFrame& world, double zs) {
  double worst = 0;
  for (size_t t = 0; t < m.tris.size(); t += 3) {
    const glm::dvec3 a = m.verts[m.tris[t]], b = m.verts[m.tris[t + 1]], c = m.verts[m.tris[t + 2]];
    const double det = (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y);
    if (det == 0) continue;
    const int64_t x0 = std::max(data.lo_x_, static_cast<int64_t>(std::min({a.x, b.x, c.x}))),
                  x1 = std::min(data.hi_x_, static_cast<int64_t>(std::max({a.x, b.x, c.x}))),
                  y0 = std::max(data.lo_y_, static_cast<int64_t>(std::min({a.y, b.y, c.y}))),
                  y1 = std::min(data.hi_y_, static_cast<int64_t>(std::max({a.y, b.y, c.y})));
    for (int64_t y = y0; y <= y1; ++y)
      for (int64_t x = x0; x <= x1; ++x) {
        const double l1 = ((x - a.x) * (c.y - a.y) - (c.x - a.x) * (y - a.y)) / det;
        const double l2 = ((b.x - a.x) * (y - a.y) - (x - a.x) * (b.y - a.y)) / det;
        if (l1 < -1e-9 || l2 < -1e-9 || l1 + l2 > 1 + 1e-9) continue;
        const auto h = data.at(x, y);
        if (!h) continue;
        const double drawn = a.z + l1 * (b.z - a.z) + l2 * (c.z - a.z);
        const glm::dvec3 p = world.key_to_world(double(x), double(y), *h, fr.view.origin);
        const double dist =
            glm::length(p * glm::dvec3(1, 1, zs / world.height_scale()) - fr.view.eye);
        worst = std::max(worst, std::abs(drawn - *h) * zs * fr.view.pixels_per_radian / dist);
      }
  }
  return worst;
}

void check_package(const std::string& pkg, int cameras, uint32_t seed) {
  cameras /= kCameraDivisor;
  ViewerSettings s;
  s.packages = {pkg};
  s.width = 400;
  s.height = 300;
  s.shading.exaggeration = 1.0;
  TerrainScene scene(s);
  const CameraPose fit = scene.initial_pose();
  const double top = scene.top_height_m();
  const FinestData finest(pkg);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  const double span = (fit.height_m - top) / 110000.0;  // degrees the fit view covers, roughly
  size_t total_triangles = 0;
  for (int i = 0; i < cameras; ++i) {
    CameraPose p = fit;
    p.lon += (u(rng) - 0.5) * span;
    p.lat += (u(rng) - 0.5) * span * 0.8;
    p.height_m = top + 100 + u(rng) * u(rng) * (fit.height_m - top) * 1.5;
    p.heading_deg = u(rng) * 360;
    p.pitch_deg = u(rng) * 80;
    scene.settings().cull = (i % 4 != 0);  // some whole-package meshes too
    const FrameResult f = scene.frame(p, Loading::kSettle, TerrainScene::Output::kSelectOnly);
    ASSERT_EQ(f.selection.waiting, 0u) << "camera " << p.str();
    const double zs = scene.world().height_scale();
    size_t cracks = 0;
    const Mesh m = weld(scene.capture(f), f, cracks);
    EXPECT_EQ(cracks, 0u) << pkg << " camera " << p.str();
    total_triangles += m.tris.size() / 3;
    if (std::getenv("GLOBE_TEST_VERBOSE"))
      std::fprintf(stderr, "camera %d %s: %zu patches, %zu triangles\n", i, p.str().c_str(),
                   f.patches.size(), m.tris.size() / 3);
    const auto [overused, tjunctions] = conformity_errors(m);
    EXPECT_EQ(overused, 0u) << pkg << " camera " << p.str();
    EXPECT_EQ(tjunctions, 0u) << pkg << " camera " << p.str();
    if (i % 3 == 0) {
      const double err = max_projected_error(m, finest, f, scene.world(), zs);
      EXPECT_LE(err, s.max_error_px + 1e-3) << pkg << " camera " << p.str();
    }
  }
  EXPECT_GT(total_triangles, size_t(cameras) * 1000) << "the cameras saw almost nothing";
}

// The globe: random cameras from 200 m to 20,000 km, a quarter of them over
// the antimeridian, a quarter over a pole, a quarter near the ground.
void check_globe(const std::string& pkg, int cameras, uint32_t seed) {
  cameras /= kCameraDivisor;
  ViewerSettings s;
  s.packages = {pkg};
  s.width = 400;
  s.height = 300;
  s.globe = true;
  TerrainScene scene(s);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  size_t total_triangles = 0;
  for (int i = 0; i < cameras; ++i) {
    CameraPose p;
    p.lon = u(rng) * 360 - 180;
    p.lat = u(rng) * 170 - 85;
    p.height_m = 200 * std::pow(1e5, u(rng));
    if (i % 4 == 1) p.lon = 179 + 2 * u(rng);  // over the antimeridian (past 180 too)
    if (i % 4 == 2) p.lat = (u(rng) < 0.5 ? -1 : 1) * (84 + 6 * u(rng));
    if (i % 4 == 3) p.height_m = 200 + 5000 * u(rng);
    p.heading_deg = u(rng) * 360;
    p.pitch_deg = u(rng) * 80;
    scene.settings().cull = (i % 5 != 0);  // some whole-globe meshes too
    const FrameResult f = scene.frame(p, Loading::kSettle, TerrainScene::Output::kSelectOnly);
    ASSERT_EQ(f.selection.waiting, 0u) << "camera " << p.str();
    size_t cracks = 0;
    const Mesh m = weld(scene.capture(f), f, cracks);
    total_triangles += m.tris.size() / 3;
    if (std::getenv("GLOBE_TEST_VERBOSE"))
      std::fprintf(stderr, "globe camera %d %s: %zu patches\n", i, p.str().c_str(),
                   f.patches.size());
    const auto [overused, tjunctions] = conformity_errors(m);
    EXPECT_EQ(cracks, 0u) << pkg << " camera " << p.str();
    EXPECT_EQ(overused, 0u) << pkg << " camera " << p.str();
    EXPECT_EQ(tjunctions, 0u) << pkg << " camera " << p.str();
  }
  EXPECT_GT(total_triangles, size_t(cameras) * 1000) << "the cameras saw almost nothing";
}

class ViewerMesh : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { context_ = create_headless_context("osmesa").release(); }
  static void TearDownTestSuite() { delete context_; }
  static HeadlessContext* context_;
};
HeadlessContext* ViewerMesh::context_ = nullptr;

TEST_F(ViewerMesh, ConformingAndWithinTauOnJacksboroWebMercator) {
  TempDir dir;
  const std::string pkg = (dir / "j.mbtiles").string();
  ASSERT_EQ(
      run(tiler() + " terrain -q " + sample("jacksboro.tif").string() + " -o " + pkg, dir.path())
          .exit_code,
      0);
  check_package(pkg, 60, 1);
}

TEST_F(ViewerMesh, ConformingAndWithinTauOnBrasiliaLocal) {
  TempDir dir;
  const std::string pkg = (dir / "b.mbtiles").string();
  ASSERT_EQ(
      run(tiler() + " terrain -q --tiling local " + sample("brasilia.tif").string() + " -o " + pkg,
          dir.path())
          .exit_code,
      0);
  check_package(pkg, 50, 2);
}

TEST_F(ViewerMesh, ConformingOnTheGlobeGeodeticAndWebMercator) {
  TempDir dir;
  const std::string geo = (dir / "g.mbtiles").string(), merc = (dir / "m.mbtiles").string();
  ASSERT_EQ(run(tiler() + " terrain -q --tiling geodetic " + sample("etopo20.tif").string() +
                    " -o " + geo,
                dir.path())
                .exit_code,
            0);
  ASSERT_EQ(run(tiler() + " terrain -q --tiling webmercator " + sample("etopo20.tif").string() +
                    " -o " + merc,
                dir.path())
                .exit_code,
            0);
  check_globe(geo, 50, 3);
  check_globe(merc, 50, 4);
}

// A key point at height h in the east-north-up frame of `origin`'s point on
// the ellipsoid, brute force in double from the textbook WGS84 formulas
// (nothing of the viewer's mapping): the reference of the precision test.
glm::dvec3 reference_enu(const tileformat::Tiling& t, double crs_per_key, double kx, double ky,
                         double h, const KeyPoint& origin) {
  const double a = 6378137.0, e2 = 0.00669437999014132, d = std::numbers::pi / 180;
  auto latlon = [&](double x, double y) {
    const double cx = t.origin_x + x * crs_per_key, cy = t.origin_y - y * crs_per_key;
    if (t.scheme == tileformat::Scheme::kWebMercator)
      return std::pair{std::atan(std::sinh(cy / a)), cx / a};
    return std::pair{cy * d, cx * d};
  };
  auto ecef = [&](double lat, double lon, double height) {
    const double n = a / std::sqrt(1 - e2 * std::sin(lat) * std::sin(lat));
    return glm::dvec3((n + height) * std::cos(lat) * std::cos(lon),
                      (n + height) * std::cos(lat) * std::sin(lon),
                      (n * (1 - e2) + height) * std::sin(lat));
  };
  const auto [lat0, lon0] = latlon(double(origin.x), double(origin.y));
  const auto [lat, lon] = latlon(kx, ky);
  const glm::dvec3 p = ecef(lat, lon, h) - ecef(lat0, lon0, 0);
  const glm::dvec3 east(-std::sin(lon0), std::cos(lon0), 0);
  const glm::dvec3 north(-std::sin(lat0) * std::cos(lon0), -std::sin(lat0) * std::sin(lon0),
                         std::cos(lat0));
  const glm::dvec3 up(std::cos(lat0) * std::cos(lon0), std::cos(lat0) * std::sin(lon0),
                      std::sin(lat0));
  return {glm::dot(p, east), glm::dot(p, north), glm::dot(p, up)};
}

// Globe precision: the vertex shader's float positions agree with the
// ellipsoid computed in double by reference_enu (textbook formulas in this
// test, no shared code) to within 5e-5 of their distance from the eye
// (0.1 px at 1280 x 720), and to 0.5 mm within 10 m of it, over the
// antimeridian, near a pole and at the equator, 2 m above the ellipsoid.
// (Where the terrain is higher the camera is inside it; the vertices are what
// they are.)
TEST_F(ViewerMesh, GlobeVerticesArePreciseNearTheEye) {
  TempDir dir;
  for (const char* tiling : {"geodetic", "webmercator"}) {
    const std::string pkg = (dir / (std::string(tiling) + ".mbtiles")).string();
    ASSERT_EQ(run(tiler() + " terrain -q --tiling " + tiling + " " +
                      sample("etopo20.tif").string() + " -o " + pkg,
                  dir.path())
                  .exit_code,
              0);
    ViewerSettings s;
    s.packages = {pkg};
    s.width = 320;
    s.height = 240;
    s.globe = true;
    s.cull = false;
    TerrainScene scene(s);
    for (const char* cam : {"179.99,45.3,2,30,80", "-12.5,84.9,2,200,70", "0.001,0.002,2,0,85"}) {
      const CameraPose p = CameraPose::parse(cam);
      const FrameResult f = scene.frame(p, Loading::kSettle, TerrainScene::Output::kSelectOnly);
      double worst = 0, worst_m = 0;
      size_t n = 0;
      for (const CapturedVertex& v : scene.capture(f)) {
        const glm::dvec3 want = reference_enu(
            scene.world().tiling(), scene.world().crs_per_key(), double(f.view.origin.x + v.key[0]),
            double(f.view.origin.y + v.key[1]), v.height_m, f.view.origin);
        const double err = glm::length(glm::dvec3(v.world[0], v.world[1], v.world[2]) - want);
        const double dist = glm::length(want - f.view.eye);
        worst = std::max(worst, err / std::max(dist, 10.0));
        worst_m = std::max(worst_m, err);
        ++n;
      }
      std::printf("%s %s: %zu vertices, worst %.2e x distance (%.2e m)\n", tiling, cam, n, worst,
                  worst_m);
      EXPECT_LT(worst, 5e-5) << tiling << " " << cam;
    }
  }
}

}  // namespace
