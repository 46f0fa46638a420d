// globe-tiler export --format quantized-mesh (docs/web.md "Quantized-mesh") as
// users run it, checked with references that share no code with it: the
// quantized-mesh decoder written from the specification (spec_readers/), the
// analytic surfaces the packages were built from (web_surfaces.hpp) and
// CesiumJS's horizon-culling test written out here. (In CesiumJS itself:
// web_cesium_test.cpp.)
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <random>
#include <set>
#include <sstream>

#include "quantized_mesh_fixtures.hpp"
#include "spec_readers/gunzip.hpp"
#include "test_support.hpp"
#include "tileformat/json.hpp"
#include "web_surfaces.hpp"

namespace {

using namespace globe_test;

constexpr double kA = 6378137.0, kB = 6356752.3142451793;

// CesiumJS's level error: a quarter of the equator / (65 * roots across) / 2^level.
double cesium_error(int z, bool mercator) {
  return kA * 2 * kPi * 0.25 / (65.0 * (mercator ? 1 : 2)) / std::ldexp(1.0, z);
}

double height_step(const std::string& pkg, const fs::path& dir) {
  return std::stod(
      run("sqlite3 " + pkg + " \"SELECT value FROM metadata WHERE name = 'globe:height_step'\"",
          dir)
          .out);
}

// A position in the space where the ellipsoid is the unit sphere; points
// below the ellipsoid count as on it (as Cesium's horizon point treats them).
std::array<double, 3> scaled(const qm::Position& p) {
  const auto e = p.ecef();
  std::array<double, 3> s{e[0] / kA, e[1] / kA, e[2] / kB};
  const double len = std::sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
  if (len < 1)
    for (double& c : s)
      c /= len;
  return s;
}

// EllipsoidalOccluder.isScaledSpacePointVisible (CesiumJS): whether a point in
// scaled space is visible from `camera` (scaled space too).
bool visible(const std::array<double, 3>& s, const std::array<double, 3>& camera) {
  const double vh2 = camera[0] * camera[0] + camera[1] * camera[1] + camera[2] * camera[2] - 1;
  const std::array<double, 3> vt{s[0] - camera[0], s[1] - camera[1], s[2] - camera[2]};
  const double vt_dot_vc = -(vt[0] * camera[0] + vt[1] * camera[1] + vt[2] * camera[2]);
  const double vt2 = vt[0] * vt[0] + vt[1] * vt[1] + vt[2] * vt[2];
  const bool occluded =
      vh2 < 0 ? vt_dot_vc > 0 : vt_dot_vc > vh2 && vt_dot_vc * vt_dot_vc / vt2 > vh2;
  return !occluded;
}

struct MeshCheck {
  const Surface& surface;
  double step;    // the package's height step
  bool mercator;  // EPSG:3857 tiles
  double margin;  // degrees kept clear of the surface's edges
  bool inside(double lon, double lat) const {
    const double lon_margin = surface.global() ? 0 : margin;
    return lon >= surface.west + lon_margin && lon <= surface.east - lon_margin &&
           lat >= surface.south + margin && lat <= surface.north - margin;
  }
};

// Everything one tile must satisfy on its own.
void check_tile(const MeshTile& t, const MeshCheck& c, int max_zoom, std::mt19937& rng) {
  const qm::Mesh& m = t.mesh;
  const std::string name =
      std::to_string(t.z) + "/" + std::to_string(t.x) + "/" + std::to_string(t.y);
  ASSERT_GT(m.vertex_count(), 3u) << name;
  ASSERT_TRUE(m.has_normals()) << name << ": no octvertexnormals extension";
  // Header: heights and bounding sphere hold every vertex.
  const auto& h = m.header;
  std::vector<qm::Position> positions;
  double outside = 0;
  for (size_t k = 0; k < m.vertex_count(); ++k) {
    positions.push_back(qm::decode_position(t.rect, m, k));
    const auto e = positions.back().ecef();
    const double d =
        std::hypot(e[0] - h.bounding_sphere_center[0], e[1] - h.bounding_sphere_center[1],
                   e[2] - h.bounding_sphere_center[2]);
    outside = std::max(outside, d - h.bounding_sphere_radius);
  }
  EXPECT_LE(outside, 0.01) << name << ": a vertex lies outside the bounding sphere";
  // Normals: unit, pointing up (within 80 degrees of the ellipsoid's normal).
  for (size_t k = 0; k < m.vertex_count(); ++k) {
    const auto& n = m.normals[k];
    const double lon = positions[k].lon_deg * kPi / 180, lat = positions[k].lat_deg * kPi / 180;
    const double up = n[0] * std::cos(lat) * std::cos(lon) + n[1] * std::cos(lat) * std::sin(lon) +
                      n[2] * std::sin(lat);
    ASSERT_GT(up, 0.17) << name << " vertex " << k << ": normal points away from up";
  }
  // Horizon occlusion point: from random cameras, whenever it is hidden
  // behind the horizon every vertex is. A tile of half the Earth has no such
  // point: the exporter then puts it 10^6 radii out (docs/web.md).
  const double hp_len = std::hypot(h.horizon_occlusion_point[0], h.horizon_occlusion_point[1],
                                   h.horizon_occlusion_point[2]);
  if (hp_len > 1e5) {
    EXPECT_GE(t.rect.east - t.rect.west, 90) << name << ": a small tile without a horizon point";
  } else {
    const std::array<double, 3> hp = h.horizon_occlusion_point;
    std::vector<std::array<double, 3>> scaled_positions;
    for (const qm::Position& p : positions)
      scaled_positions.push_back(scaled(p));
    std::uniform_real_distribution<double> unit(-1, 1), far(1.0005, 3);
    for (int k = 0; k < 64; ++k) {
      std::array<double, 3> cam{unit(rng), unit(rng), unit(rng)};
      const double len = std::sqrt(cam[0] * cam[0] + cam[1] * cam[1] + cam[2] * cam[2]);
      const double r = far(rng);
      for (double& v : cam)
        v *= r / len;
      if (visible(hp, cam)) continue;
      for (size_t v = 0; v < positions.size(); ++v)
        ASSERT_FALSE(visible(scaled_positions[v], cam))
            << name << ": vertex " << v
            << " is visible from a camera that cannot see the horizon occlusion point";
    }
  }
  // The TIN within CesiumJS's geometric error of its level: on a 17 x 17
  // grid of the tile, the mesh against the source.
  const double quant = t.quantum() / 2;
  const TriangleIndex index(m);
  const double bound = cesium_error(t.z, c.mercator) + c.step / 2 + quant + 0.5;
  for (int j = 0; j <= 16; ++j)
    for (int i = 0; i <= 16; ++i) {
      const double lon = t.rect.west + (t.rect.east - t.rect.west) * i / 16;
      const double lat = t.rect.south + (t.rect.north - t.rect.south) * j / 16;
      if (!c.inside(lon, lat)) continue;
      const std::optional<double> got = mesh_height_at(
          t, lon, lat, [&](size_t k) { return t.vertex_height(k); }, &index);
      ASSERT_TRUE(got) << name << ": no triangle covers " << lon << ", " << lat;
      EXPECT_LE(std::fabs(*got - c.surface.bilinear(lon, lat)), bound)
          << name << " at " << lon << ", " << lat;
    }
  // The finest zoom: every vertex is the source's height there, within the
  // height step, the height quantization and the slope times half a u, v unit
  // (the vertex sits at a sample; its decoded position is rounded).
  if (t.z != max_zoom) return;
  const double position =
      c.surface.amp *
      (c.surface.kx * (t.rect.east - t.rect.west) + c.surface.ky * (t.rect.north - t.rect.south)) /
      (2 * qm::kQuantizedMax);
  for (size_t k = 0; k < m.vertex_count(); ++k) {
    const double lon = t.vertex_lon(k), lat = t.vertex_lat(k);
    if (!c.inside(lon, lat)) continue;
    EXPECT_NEAR(t.vertex_height(k), c.surface.bilinear(lon, lat),
                c.step / 2 + quant + position + 0.02)
        << name << " vertex " << k << " at " << lon << ", " << lat;
  }
}

// Vertices of one edge of a tile in order along it: (position along the edge
// in 0..32767, height, normal bytes).
struct EdgeVertex {
  int along;
  double height;
  int oct_x, oct_y;
};
std::vector<EdgeVertex> edge_vertices(const MeshTile& t, char edge) {
  const qm::Mesh& m = t.mesh;
  const std::vector<uint32_t>& list = edge == 'W'   ? m.west_indices
                                      : edge == 'E' ? m.east_indices
                                      : edge == 'S' ? m.south_indices
                                                    : m.north_indices;
  std::vector<EdgeVertex> out;
  for (uint32_t k : list)
    out.push_back({edge == 'W' || edge == 'E' ? m.v[k] : m.u[k], t.vertex_height(k),
                   m.oct_normals[2 * k], m.oct_normals[2 * k + 1]});
  std::sort(out.begin(), out.end(),
            [](const EdgeVertex& a, const EdgeVertex& b) { return a.along < b.along; });
  return out;
}

// Neighbours share their edges exactly: the same vertices (no cracks), heights
// within both tiles' quantization, the same normal (no lighting seams).
void check_shared_edge(const MeshTile& a, char ea, const MeshTile& b, char eb) {
  const auto va = edge_vertices(a, ea), vb = edge_vertices(b, eb);
  const std::string name = std::to_string(a.z) + "/" + std::to_string(a.x) + "/" +
                           std::to_string(a.y) + " " + ea + " | " + std::to_string(b.z) + "/" +
                           std::to_string(b.x) + "/" + std::to_string(b.y) + " " + eb;
  ASSERT_EQ(va.size(), vb.size()) << name << ": the tiles cut their shared edge differently";
  for (size_t k = 0; k < va.size(); ++k) {
    ASSERT_EQ(va[k].along, vb[k].along) << name << " vertex " << k;
    EXPECT_NEAR(va[k].height, vb[k].height, a.quantum() / 2 + b.quantum() / 2 + 1e-3)
        << name << " vertex " << k;
    // The same normal: equal bytes, or (on the octahedron's folds, where two
    // codes decode alike) the same decoded direction.
    const auto na = qm::oct_decode(uint8_t(va[k].oct_x), uint8_t(va[k].oct_y));
    const auto nb = qm::oct_decode(uint8_t(vb[k].oct_x), uint8_t(vb[k].oct_y));
    EXPECT_GT(na[0] * nb[0] + na[1] * nb[1] + na[2] * nb[2], std::cos(0.1 * kPi / 180))
        << name << " vertex " << k << ": normals differ (" << va[k].oct_x << "," << va[k].oct_y
        << " against " << vb[k].oct_x << "," << vb[k].oct_y << ")";
  }
}

// layer.json against the tiles present.
void check_layer_json(const fs::path& dir, const MeshTiles& tiles, bool mercator) {
  const tileformat::JsonValue layer = tileformat::JsonValue::parse(read_file(dir / "layer.json"));
  EXPECT_EQ(layer.find("format")->string(), "quantized-mesh-1.0");
  EXPECT_EQ(layer.find("version")->string(), "1.0.0");
  EXPECT_EQ(layer.find("scheme")->string(), "tms");
  EXPECT_EQ(layer.find("projection")->string(), mercator ? "EPSG:3857" : "EPSG:4326");
  EXPECT_NE(layer.find("tiles")->array().at(0).string().find("{version}"), std::string::npos);
  bool normals = false;
  for (const auto& e : layer.find("extensions")->array()) {
    EXPECT_NE(e.string(), "metadata") << "metadata listed without metadataAvailability";
    normals = normals || e.string() == "octvertexnormals";
  }
  EXPECT_TRUE(normals);
  std::set<std::tuple<int, uint32_t, uint32_t>> listed;
  const auto& available = layer.find("available")->array();
  for (size_t z = 0; z < available.size(); ++z)
    for (const auto& r : available[z].array())
      for (uint32_t y = uint32_t(r.find("startY")->number()); y <= r.find("endY")->number(); ++y)
        for (uint32_t x = uint32_t(r.find("startX")->number()); x <= r.find("endX")->number(); ++x)
          EXPECT_TRUE(listed.insert({int(z), x, y}).second) << "listed twice: " << z;
  std::set<std::tuple<int, uint32_t, uint32_t>> present;
  for (const auto& [k, _] : tiles)
    present.insert(k);
  EXPECT_EQ(listed, present) << "available does not list exactly the tiles written";
  if (!mercator) {  // Cesium's two geodetic roots
    EXPECT_TRUE(tiles.count({0, 0, 0}) && tiles.count({0, 1, 0}));
  }
}

// Exports the package to DIR and checks every tile, every shared edge and layer.json.
void check_mesh_export(const fs::path& pkg, const MeshCheck& c, const fs::path& dir) {
  const fs::path out = dir / (pkg.stem().string() + "-qm");
  const RunResult r = run(tiler() + " export -q " + pkg.string() + " --format quantized-mesh -o " +
                              out.string() + " --force",
                          dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const MeshTiles tiles = read_mesh_folder(out, c.mercator);
  ASSERT_FALSE(tiles.empty());
  check_layer_json(out, tiles, c.mercator);
  int max_zoom = 0;
  for (const auto& [k, t] : tiles)
    max_zoom = std::max(max_zoom, t.z);
  std::mt19937 rng(7);
  size_t edges = 0;
  for (const auto& [k, t] : tiles) {
    check_tile(t, c, max_zoom, rng);
    if (::testing::Test::HasFatalFailure()) return;
    const uint32_t cols = c.mercator ? (1u << t.z) : (2u << t.z);
    const auto east = tiles.find({t.z, (t.x + 1) % cols, t.y});
    if (east != tiles.end()) check_shared_edge(t, 'E', east->second, 'W'), ++edges;
    const auto north = tiles.find({t.z, t.x, t.y + 1});
    if (north != tiles.end()) check_shared_edge(t, 'N', north->second, 'S'), ++edges;
    if (::testing::Test::HasFatalFailure()) return;
  }
  EXPECT_GT(edges, tiles.size() / 2);
  std::cerr << pkg << ": " << tiles.size() << " tiles, zoom 0.." << max_zoom << ", " << edges
            << " shared edges checked\n";
}

}  // namespace

// A regional surface, geodetic and webmercator: every tile decodes (spec
// reader), is valid, within Cesium's error of the source, exact at the
// finest zoom, and cut like its neighbours along every shared edge.
TEST(QuantizedMesh, RegionalTilesAreValidExactAndShareTheirEdges) {
  const fs::path& d = surface_dem();
  TempDir dir("qm-regional");
  for (const bool mercator : {false, true}) {
    SCOPED_TRACE(mercator ? "webmercator" : "geodetic");
    const fs::path pkg = d / (mercator ? "mercator.mbtiles" : "geodetic.mbtiles");
    check_mesh_export(pkg, {kRegional, height_step(pkg.string(), dir.path()), mercator, 0.05},
                      dir.path());
  }
}

// The whole globe: tiles across the antimeridian share their edge (x wraps),
// the pole tiles have defined normals, both roots exist.
TEST(QuantizedMesh, GlobalTilesWrapTheAntimeridianAndReachThePoles) {
  const fs::path d = surface_packages(kGlobal, "global");
  TempDir dir("qm-global");
  for (const bool mercator : {false, true}) {
    SCOPED_TRACE(mercator ? "webmercator" : "geodetic");
    const fs::path pkg = d / (mercator ? "mercator.mbtiles" : "geodetic.mbtiles");
    check_mesh_export(pkg, {kGlobal, height_step(pkg.string(), dir.path()), mercator, 0.6},
                      dir.path());
  }
}

// Same bytes for any thread count; MBTiles holds the same tiles and layer.json.
TEST(QuantizedMesh, SameTilesForAnyThreadsAndInMbtiles) {
  const fs::path& d = surface_dem();
  TempDir dir("qm-threads");
  const std::string pkg = (d / "geodetic.mbtiles").string();
  const fs::path a = dir.path() / "a" / "out", b = dir.path() / "b" / "out";
  ASSERT_TRUE(
      run_all({tiler() + " export -q -j 1 " + pkg + " --format quantized-mesh -o " + a.string(),
               tiler() + " export -q -j 3 " + pkg + " --format quantized-mesh -o " + b.string(),
               tiler() + " export -q " + pkg + " --format quantized-mesh -o " +
                   (dir.path() / "c.mbtiles").string()},
              dir.path()));
  size_t files = 0;
  for (const auto& e : fs::recursive_directory_iterator(a)) {
    if (!e.is_regular_file()) continue;
    const fs::path rel = fs::relative(e.path(), a);
    ASSERT_EQ(read_file(e.path()), read_file(b / rel)) << rel;
    ++files;
  }
  EXPECT_GT(files, 10u);
  const RunResult count =
      run("sqlite3 " + (dir.path() / "c.mbtiles").string() + " 'SELECT count(*) FROM tiles'",
          dir.path());
  EXPECT_EQ(std::stoul(count.out), files - 2) << "every tile but layer.json and metadata.json";
  const RunResult layer = run("sqlite3 " + (dir.path() / "c.mbtiles").string() +
                                  " \"SELECT value FROM metadata WHERE name = 'layer.json'\"",
                              dir.path());
  std::string expected = read_file(a / "layer.json");
  expected.replace(expected.find("\"out\""), 5, "\"c\"");
  EXPECT_EQ(layer.out, expected + "\n");
}

// --gzip-level: the same tiles inside the gzip, at another deflate level
// (more bytes at 1 than at the default 6); out of range, or with a PNG
// format, a usage error (exit 2).
TEST(QuantizedMesh, GzipLevelKeepsTheTilesAndTradesBytes) {
  const fs::path& d = surface_dem();
  TempDir dir("qm-gzip");
  const std::string pkg = (d / "geodetic.mbtiles").string();
  const fs::path a = dir.path() / "six", b = dir.path() / "one";
  ASSERT_TRUE(run_all(
      {tiler() + " export -q " + pkg + " --format quantized-mesh --gzip -o " + a.string(),
       tiler() + " export -q " + pkg + " --format quantized-mesh --gzip-level 1 -o " + b.string()},
      dir.path()));
  size_t files = 0, bytes_six = 0, bytes_one = 0;
  for (const auto& e : fs::recursive_directory_iterator(a)) {
    if (!e.is_regular_file() || e.path().extension() != ".terrain") continue;
    const fs::path rel = fs::relative(e.path(), a);
    const std::string six = read_file(e.path()), one = read_file(b / rel);
    ASSERT_EQ(spec_readers::gunzip(six, rel.string(), 1 << 26),
              spec_readers::gunzip(one, rel.string(), 1 << 26))
        << rel;
    bytes_six += six.size(), bytes_one += one.size();
    ++files;
  }
  EXPECT_GT(files, 10u);
  EXPECT_GT(bytes_one, bytes_six);
  for (const char* bad :
       {" --format quantized-mesh --gzip-level 0", " --format quantized-mesh --gzip-level 10",
        " --format terrarium --gzip"}) {
    const RunResult r = run(
        tiler() + " export -q " + pkg + bad + " -o " + (dir.path() / "bad").string(), dir.path());
    EXPECT_EQ(r.exit_code, 2) << bad << ": " << r.err;
    EXPECT_FALSE(fs::exists(dir.path() / "bad")) << bad;
  }
}

// Clear errors and nothing written: a local tiling, a PMTiles output.
TEST(QuantizedMesh, RefusesLocalTilingsAndPmtiles) {
  TempDir dir("qm-bad");
  const fs::path& d = surface_dem();
  const RunResult pm = run(tiler() + " export " + (d / "geodetic.mbtiles").string() +
                               " --format quantized-mesh -o " + (dir.path() / "t.pmtiles").string(),
                           dir.path());
  EXPECT_EQ(pm.exit_code, 2) << pm.err;
  EXPECT_NE(pm.err.find("layer.json"), std::string::npos) << pm.err;
  EXPECT_FALSE(fs::exists(dir.path() / "t.pmtiles"));

  ASSERT_TRUE(run_all({tiler() + " terrain -q --tiling local " + (d / "surface.tif").string() +
                       " -o " + (dir.path() / "local.mbtiles").string()},
                      dir.path()));
  const RunResult local = run(tiler() + " export " + (dir.path() / "local.mbtiles").string() +
                                  " --format quantized-mesh -o " + (dir.path() / "out").string(),
                              dir.path());
  EXPECT_EQ(local.exit_code, 2) << local.err;
  EXPECT_NE(local.err.find("local tiling"), std::string::npos) << local.err;
  EXPECT_FALSE(fs::exists(dir.path() / "out"));
}

// --watermask: water polygons (a box over the surface's west part) become
// each tile's water mask (extension watermask, listed in layer.json): every
// pixel of every tile, at its centre, water inside the box and land outside
// (pixels within half a pixel of the box's edges may be either); tiles all
// land or all water hold one byte.
TEST(QuantizedMesh, WaterMaskFromPolygons) {
  TempDir dir("qm-water");
  std::ofstream(dir / "water.geojson")
      << R"({"type":"FeatureCollection","features":[{"type":"Feature","properties":{},)"
      << R"("geometry":{"type":"Polygon","coordinates":[[[9,44],[12,44],[12,47.3],[9,47.3],[9,44]]]}}]})";
  const fs::path out = dir / "qm";
  const RunResult r = run(tiler() + " export -q " + (surface_dem() / "geodetic.mbtiles").string() +
                              " --format quantized-mesh -o " + out.string() + " --watermask " +
                              (dir / "water.geojson").string(),
                          dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(read_file(out / "layer.json").find("\"watermask\""), std::string::npos);
  const MeshTiles tiles = read_mesh_folder(out, false);
  size_t one_byte = 0, full = 0, wrong = 0;
  for (const auto& [k, t] : tiles) {
    ASSERT_TRUE(t.mesh.water_mask.has_value()) << t.z << "/" << t.x << "/" << t.y;
    const std::vector<uint8_t>& mask = *t.mesh.water_mask;
    (mask.size() == 1 ? one_byte : full)++;
    const double w = t.rect.east - t.rect.west, h = t.rect.north - t.rect.south;
    for (int row = 0; row < 256; ++row)
      for (int col = 0; col < 256; ++col) {
        const double lon = t.rect.west + (col + 0.5) / 256 * w;
        const double lat = t.rect.north - (row + 0.5) / 256 * h;
        const double dx = w / 256 / 2 + 1e-9, dy = h / 256 / 2 + 1e-9;
        const bool in = lon > 9 + dx && lon < 12 - dx && lat > 44 + dy && lat < 47.3 - dy;
        const bool out_ = lon < 9 - dx || lon > 12 + dx || lat < 44 - dy || lat > 47.3 + dy;
        const uint8_t got = mask.size() == 1 ? mask[0] : mask[size_t(row) * 256 + col];
        if ((in && got != 255) || (out_ && got != 0)) ++wrong;
      }
  }
  EXPECT_EQ(wrong, 0u);
  EXPECT_GT(one_byte, 0u);
  EXPECT_GT(full, 0u);
}
