// globe-view's quantized-mesh source (viewer/data/quantized_mesh_decode,
// mesh_grid, quantized_mesh_reader) against references that share no code
// with it: the decoder written from the specification (spec_readers/), a
// brute-force point location in doubles written here, and the terrain
// package the tiles were exported from (globe-tiler terrain + export
// --format quantized-mesh), served by fault_server (a folder) and by
// globe-serve (cut on the fly). Touches only its temporary folders and the
// shared fixture folder of this binary.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <iostream>
#include <map>
#include <random>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "data/mesh_grid.hpp"
#include "data/quantized_mesh_decode.hpp"
#include "data/quantized_mesh_reader.hpp"
#include "fault_server_fixtures.hpp"
#include "net/http_client.hpp"
#include "runtime/errors.hpp"
#include "serve_fixtures.hpp"
#include "spec_readers/quantized_mesh_reader.hpp"
#include "test_support.hpp"
#include "tileformat/error.hpp"
#include "tileformat/mblock.hpp"
#include "tileformat/metadata.hpp"
#include "tileformat/package.hpp"

namespace {

using namespace globe_test;
using globe::viewer::decode_quantized_mesh;
using globe::viewer::mesh_grid;
using globe::viewer::QuantizedMesh;
using globe::viewer::QuantizedMeshReader;
using tileformat::TileId;
namespace qm = spec_readers::quantized_mesh;

using Bytes = std::vector<uint8_t>;

Bytes file_bytes(const fs::path& p) {
  const std::string s = read_file(p);
  return {s.begin(), s.end()};
}

// etopo20 as a geodetic package of 65² blocks (zooms 0..3; tiles like
// ctb's), its quantized-mesh export plain and gzipped, and a web mercator
// package of 257² blocks (zooms 0..1: tiles of 66,049 vertices, 32-bit
// indices) with its export. Built once per build tree.
const fs::path& fixtures() {
  static const fs::path dir = shared_folder("quantized_mesh_reader", [](const fs::path& d) {
    const std::string etopo = sample("etopo20.tif").string();
    const auto at = [&](const char* name) { return " " + (d / name).string(); };
    return run_all(
        {tiler() + " terrain -q " + etopo + " --tiling geodetic --block-size 65 --max-zoom 3 -o" +
             at("geodetic.mbtiles"),
         tiler() + " export -q" + at("geodetic.mbtiles") + " --format quantized-mesh -o" +
             at("geodetic-qm"),
         tiler() + " export -q" + at("geodetic.mbtiles") + " --format quantized-mesh --gzip -o" +
             at("geodetic-gz"),
         tiler() + " terrain -q " + etopo + " --max-zoom 1 -o" + at("mercator.mbtiles"),
         tiler() + " export -q" + at("mercator.mbtiles") + " --format quantized-mesh -o" +
             at("mercator-qm")},
        d);
  });
  return dir;
}

struct TileFile {
  int z = 0;
  uint32_t x = 0, y_tms = 0;
  fs::path path;
};

std::vector<TileFile> tile_files(const fs::path& dir) {
  std::vector<TileFile> out;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    if (e.path().extension() != ".terrain") continue;
    const fs::path rel = fs::relative(e.path(), dir);
    auto it = rel.begin();
    TileFile t;
    t.z = std::stoi((it++)->string());
    t.x = uint32_t(std::stoul((it++)->string()));
    t.y_tms = uint32_t(std::stoul(it->stem().string()));
    t.path = e.path();
    out.push_back(t);
  }
  std::sort(out.begin(), out.end(), [](const TileFile& a, const TileFile& b) {
    return std::tie(a.z, a.x, a.y_tms) < std::tie(b.z, b.x, b.y_tms);
  });
  return out;
}

// ------------------------------------------------ a writer for test tiles ----

// A tile as written here: vertices as final values, triangles as vertex
// indices (written with the high-water mark after renumbering the vertices
// in first-use order, unless `codes` gives the index codes as they are).
struct TestMesh {
  float min_h = 0, max_h = 100;
  std::vector<uint16_t> u, v, h;
  std::vector<uint32_t> tris;
  std::vector<uint32_t> codes;  // non-empty: written instead of encoding tris
  std::vector<std::pair<uint8_t, Bytes>> extensions;
};

void put_u16(Bytes& b, uint32_t v) {
  b.push_back(uint8_t(v));
  b.push_back(uint8_t(v >> 8));
}
void put_u32(Bytes& b, uint32_t v) {
  for (int i = 0; i < 4; ++i)
    b.push_back(uint8_t(v >> (8 * i)));
}
void put_f64(Bytes& b, double d) {
  const uint64_t v = std::bit_cast<uint64_t>(d);
  for (int i = 0; i < 8; ++i)
    b.push_back(uint8_t(v >> (8 * i)));
}
uint16_t zig_zag(int32_t d) {
  return uint16_t((uint32_t(d) << 1) ^ uint32_t(d >> 31));
}

// Vertices renumbered in the order the triangles first use them (unused ones last).
TestMesh in_first_use_order(TestMesh m) {
  const size_t n = m.u.size();
  std::vector<int64_t> to(n, -1);
  std::vector<uint32_t> order;
  for (uint32_t& k : m.tris) {
    if (to[k] < 0) {
      to[k] = int64_t(order.size());
      order.push_back(k);
    }
    k = uint32_t(to[k]);
  }
  for (uint32_t k = 0; k < n; ++k)
    if (to[k] < 0) order.push_back(k);
  TestMesh r = m;
  for (size_t i = 0; i < n; ++i) {
    r.u[i] = m.u[order[i]];
    r.v[i] = m.v[order[i]];
    r.h[i] = m.h[order[i]];
  }
  return r;
}

Bytes write_mesh(const TestMesh& in) {
  const TestMesh m = in.codes.empty() ? in_first_use_order(in) : in;
  Bytes b;
  for (int i = 0; i < 3; ++i)
    put_f64(b, 0);
  uint32_t f;
  std::memcpy(&f, &m.min_h, 4);
  put_u32(b, f);
  std::memcpy(&f, &m.max_h, 4);
  put_u32(b, f);
  for (double d : {0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0})
    put_f64(b, d);
  const uint32_t n = uint32_t(m.u.size());
  put_u32(b, n);
  for (const auto* values : {&m.u, &m.v, &m.h}) {
    int32_t prev = 0;
    for (uint16_t x : *values) {
      put_u16(b, zig_zag(int32_t(x) - prev));
      prev = x;
    }
  }
  const bool wide = n > 65536;
  while (b.size() % (wide ? 4 : 2))
    b.push_back(0);
  std::vector<uint32_t> codes = m.codes;
  if (codes.empty()) {
    uint32_t highest = 0;
    for (uint32_t k : m.tris) {
      codes.push_back(highest - k);
      if (k == highest) ++highest;
    }
  }
  put_u32(b, uint32_t(codes.size() / 3));
  auto index = [&](uint32_t k) { wide ? put_u32(b, k) : put_u16(b, k); };
  for (uint32_t c : codes)
    index(c);
  for (int edge = 0; edge < 4; ++edge) {  // west, south, east, north
    std::vector<uint32_t> list;
    for (uint32_t k = 0; k < n; ++k) {
      const uint16_t c = (edge % 2 == 0) ? m.u[k] : m.v[k];
      if (c == (edge < 2 ? 0 : qm::kQuantizedMax)) list.push_back(k);
    }
    put_u32(b, uint32_t(list.size()));
    for (uint32_t k : list)
      index(k);
  }
  for (const auto& [id, data] : m.extensions) {
    b.push_back(id);
    put_u32(b, uint32_t(data.size()));
    b.insert(b.end(), data.begin(), data.end());
  }
  return b;
}

// The boundary of the unit square as a ring of vertices with the given
// positions along each edge (each list ascending, without the corners), and
// one inner vertex at (cu, cv): a fan, every triangle non-degenerate.
// Heights from `height(u, v)`.
TestMesh fan_mesh(const std::vector<uint16_t>& west_v, const std::vector<uint16_t>& south_u,
                  const std::vector<uint16_t>& east_v, const std::vector<uint16_t>& north_u,
                  uint16_t cu, uint16_t cv, const std::function<uint16_t(int, int)>& height) {
  const int m = qm::kQuantizedMax;
  std::vector<std::pair<int, int>> ring{{0, 0}};  // counter-clockwise from the south-west
  for (uint16_t u : south_u)
    ring.push_back({u, 0});
  ring.push_back({m, 0});
  for (uint16_t v : east_v)
    ring.push_back({m, v});
  ring.push_back({m, m});
  for (auto it = north_u.rbegin(); it != north_u.rend(); ++it)
    ring.push_back({*it, m});
  ring.push_back({0, m});
  for (auto it = west_v.rbegin(); it != west_v.rend(); ++it)
    ring.push_back({0, *it});
  TestMesh t;
  t.min_h = -500;
  t.max_h = 2500;
  for (const auto& [u, v] : ring) {
    t.u.push_back(uint16_t(u));
    t.v.push_back(uint16_t(v));
    t.h.push_back(height(u, v));
  }
  t.u.push_back(cu);
  t.v.push_back(cv);
  t.h.push_back(height(cu, cv));
  const uint32_t centre = uint32_t(ring.size());
  for (uint32_t k = 0; k < ring.size(); ++k)
    t.tris.insert(t.tris.end(), {centre, k, uint32_t((k + 1) % ring.size())});
  return t;
}

// A k x k lattice with jittered inner vertices, each cell split along a
// random diagonal; `hole` of the triangles dropped, `degenerate` zero-area
// triangles added.
TestMesh lattice_mesh(int k, uint32_t seed, double hole, int degenerate) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(0, 1);
  const double cell = double(qm::kQuantizedMax) / (k - 1);
  TestMesh t;
  t.min_h = -1234.5f;
  t.max_h = 4321.25f;
  for (int j = 0; j < k; ++j)
    for (int i = 0; i < k; ++i) {
      double u = i * cell, v = j * cell;
      if (i > 0 && i < k - 1) u += (unit(rng) - 0.5) * cell * 0.3;
      if (j > 0 && j < k - 1) v += (unit(rng) - 0.5) * cell * 0.3;
      t.u.push_back(uint16_t(std::lround(u)));
      t.v.push_back(uint16_t(std::lround(v)));
      t.h.push_back(uint16_t(rng() % 32768));
    }
  auto at = [k](int i, int j) { return uint32_t(j * k + i); };
  for (int j = 0; j + 1 < k; ++j)
    for (int i = 0; i + 1 < k; ++i) {
      const uint32_t a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1), d = at(i, j + 1);
      std::vector<std::array<uint32_t, 3>> two;
      if (rng() % 2)
        two = {{a, b, c}, {a, c, d}};
      else
        two = {{a, b, d}, {b, c, d}};
      for (const auto& tri : two)
        if (unit(rng) >= hole) t.tris.insert(t.tris.end(), tri.begin(), tri.end());
    }
  for (int g = 0; g < degenerate; ++g) {  // a repeated vertex; three along the south edge
    const uint32_t a = rng() % t.u.size(), b = rng() % t.u.size();
    t.tris.insert(t.tris.end(), {a, a, b});
    if (k >= 3) t.tris.insert(t.tris.end(), {at(0, 0), at(1, 0), at(2, 0)});
  }
  return t;
}

QuantizedMesh decoded(const TestMesh& t) {
  return decode_quantized_mesh(write_mesh(t));
}

// ------------------------------------------- brute-force point location ----

// The mesh's height at (u, v) (real-valued quantized coordinates): the
// triangle holding it found among all of them in doubles, barycentric;
// nullopt where none does (beyond a tolerance of 1e-9).
std::optional<double> brute_height(const QuantizedMesh& m, double pu, double pv) {
  double best = -1e300, height = 0;
  for (size_t t = 0; t + 2 < m.triangles.size(); t += 3) {
    const uint32_t a = m.triangles[t], b = m.triangles[t + 1], c = m.triangles[t + 2];
    const double ua = m.u[a], va = m.v[a], ub = m.u[b], vb = m.v[b], uc = m.u[c], vc = m.v[c];
    const double d = (vb - vc) * (ua - uc) + (uc - ub) * (va - vc);
    if (d == 0) continue;
    const double l1 = ((vb - vc) * (pu - uc) + (uc - ub) * (pv - vc)) / d;
    const double l2 = ((vc - va) * (pu - uc) + (ua - uc) * (pv - vc)) / d;
    const double l3 = 1 - l1 - l2;
    const double worst = std::min({l1, l2, l3});
    if (worst > best) {
      best = worst;
      height = l1 * m.height_m(a) + l2 * m.height_m(b) + l3 * m.height_m(c);
    }
  }
  if (best < -1e-9) return std::nullopt;
  return height;
}

struct Stats {
  std::vector<double> d;
  void add(double x) { d.push_back(x); }
  double max() const { return d.empty() ? 0 : *std::max_element(d.begin(), d.end()); }
  double p99() const {
    if (d.empty()) return 0;
    std::vector<double> s = d;
    const size_t k = std::min(s.size() - 1, size_t(0.99 * double(s.size())));
    std::nth_element(s.begin(), s.begin() + long(k), s.end());
    return s[k];
  }
};

// Grid points checked: corners, edge points (at most 64 per edge), and
// `random` others.
std::vector<std::pair<int, int>> check_points(int size, int random, std::mt19937& rng) {
  std::vector<std::pair<int, int>> p;
  const int step = std::max(1, (size - 1) / 64);
  for (int i = 0; i < size; i += step) {
    p.push_back({i, 0});
    p.push_back({i, size - 1});
    p.push_back({0, i});
    p.push_back({size - 1, i});
  }
  for (int k = 0; k < random; ++k)
    p.push_back({int(rng() % size), int(rng() % size)});
  return p;
}

// mesh_grid against brute_height at the points; returns the largest difference.
double check_against_brute_force(const QuantizedMesh& m, int size, int random, std::mt19937& rng,
                                 const std::string& name, const std::vector<double>& rows = {}) {
  const std::vector<float> g = mesh_grid(m, size, rows);
  EXPECT_EQ(g.size(), size_t(size) * size);
  double worst = 0;
  for (const auto& [i, j] : check_points(size, random, rng)) {
    const double pu = double(i) * qm::kQuantizedMax / (size - 1);
    const double pv =
        rows.empty() ? double(size - 1 - j) * qm::kQuantizedMax / (size - 1) : rows[size_t(j)];
    const std::optional<double> want = brute_height(m, pu, pv);
    const float got = g[size_t(j) * size + size_t(i)];
    if (!want) {
      EXPECT_TRUE(std::isnan(got))
          << name << " (" << i << ", " << j << "): in no triangle, got " << got;
      continue;
    }
    if (std::isnan(got)) {
      ADD_FAILURE() << name << " (" << i << ", " << j << "): NaN, brute force " << *want;
      continue;
    }
    const double diff = std::abs(got - *want);
    worst = std::max(worst, diff);
    EXPECT_LE(diff, 1e-3 + 1e-6 * std::abs(*want)) << name << " (" << i << ", " << j << ")";
  }
  return worst;
}

// ------------------------------------------------------------------ tests ----

// (a) Every exported tile (geodetic 65², plain and gzipped; web mercator
// 257² with 32-bit indices) decodes to what the spec reader decodes.
TEST(QuantizedMeshReader, DecoderAgreesWithTheSpecReaderOnExportedTiles) {
  size_t tiles = 0, wide = 0;
  for (const char* folder : {"geodetic-qm", "geodetic-gz", "mercator-qm"}) {
    const std::vector<TileFile> files = tile_files(fixtures() / folder);
    ASSERT_FALSE(files.empty()) << folder;
    for (const TileFile& f : files) {
      const std::string bytes = read_file(f.path);
      const qm::Mesh want = qm::decode(bytes);
      const QuantizedMesh got = decode_quantized_mesh(Bytes(bytes.begin(), bytes.end()));
      const std::string name = std::string(folder) + " " + f.path.string();
      ASSERT_EQ(got.u, want.u) << name;
      ASSERT_EQ(got.v, want.v) << name;
      ASSERT_EQ(got.height, want.height) << name;
      ASSERT_EQ(got.triangles, want.triangles) << name;
      ASSERT_EQ(got.west, want.west_indices) << name;
      ASSERT_EQ(got.south, want.south_indices) << name;
      ASSERT_EQ(got.east, want.east_indices) << name;
      ASSERT_EQ(got.north, want.north_indices) << name;
      ASSERT_EQ(got.oct_normals, want.oct_normals) << name;
      ASSERT_EQ(got.header.min_height, want.header.min_height) << name;
      ASSERT_EQ(got.header.max_height, want.header.max_height) << name;
      ASSERT_EQ(got.header.center, want.header.center) << name;
      ASSERT_EQ(got.header.bounding_sphere_radius, want.header.bounding_sphere_radius) << name;
      ASSERT_EQ(got.header.horizon_occlusion_point, want.header.horizon_occlusion_point) << name;
      ++tiles;
      wide += want.indices_are_32bit;
    }
  }
  EXPECT_GT(wide, 0u) << "no tile with 32-bit indices was checked";
  std::cerr << tiles << " exported tiles decoded alike, " << wide << " with 32-bit indices\n";
}

// (a) Tiles written here: 16-bit and 32-bit indices (odd vertex count: 2
// bytes of padding), extensions known and unknown, gzip of two members.
TEST(QuantizedMeshReader, DecoderAgreesWithTheSpecReaderOnWrittenTiles) {
  for (const int k : {5, 257, 259}) {  // 259² = 67,081 vertices: 32-bit
    TestMesh t = lattice_mesh(k, uint32_t(k), 0.1, 3);
    Bytes normals(2 * t.u.size(), 0x80);
    t.extensions = {{1, normals}, {9, Bytes{1, 2, 3}}, {2, Bytes{255}}};
    Bytes meta;
    put_u32(meta, 2);
    meta.push_back('{');
    meta.push_back('}');
    t.extensions.push_back({4, meta});
    const Bytes b = write_mesh(t);
    const qm::Mesh want = qm::decode(std::string(b.begin(), b.end()));
    const QuantizedMesh got = decode_quantized_mesh(b);
    EXPECT_EQ(want.indices_are_32bit, k > 256);
    EXPECT_EQ(got.u, want.u);
    EXPECT_EQ(got.v, want.v);
    EXPECT_EQ(got.height, want.height);
    EXPECT_EQ(got.triangles, want.triangles);
    EXPECT_EQ(got.west, want.west_indices);
    EXPECT_EQ(got.north, want.north_indices);
    EXPECT_EQ(got.oct_normals, normals);
    ASSERT_TRUE(got.water_mask);
    EXPECT_EQ(*got.water_mask, Bytes{255});
    ASSERT_TRUE(got.metadata_json);
    EXPECT_EQ(*got.metadata_json, "{}");
  }
  // Two gzip members are one body (gzip -c a b).
  const Bytes plain = file_bytes(tile_files(fixtures() / "geodetic-qm").front().path);
  const Bytes gz = file_bytes(tile_files(fixtures() / "geodetic-gz").front().path);
  ASSERT_EQ(globe::viewer::gunzip_if_gzipped(gz), plain);
  const Bytes head(plain.begin(), plain.begin() + 1000);
  TempDir dir;
  std::ofstream(dir / "head", std::ios::binary)
      .write(reinterpret_cast<const char*>(head.data()), long(head.size()));
  std::ofstream(dir / "tail", std::ios::binary)
      .write(reinterpret_cast<const char*>(plain.data() + 1000), long(plain.size() - 1000));
  ASSERT_EQ(
      run("(cd " + dir.path().string() + " && gzip -c head > two.gz && gzip -c tail >> two.gz)",
          dir.path())
          .exit_code,
      0);
  EXPECT_EQ(decode_quantized_mesh(file_bytes(dir / "two.gz")).triangles,
            decode_quantized_mesh(plain).triangles);
}

// (b) The grid against a brute force in doubles: exported tiles of every
// zoom, and lattices with holes and zero-area triangles, at several sizes.
TEST(QuantizedMeshReader, GridMatchesBruteForcePointLocation) {
  std::mt19937 rng(11);
  double worst = 0;
  size_t meshes = 0;
  const std::vector<TileFile> files = tile_files(fixtures() / "geodetic-qm");
  for (size_t f = 0; f < files.size(); f += 17) {  // 10 of the 170
    const QuantizedMesh m = decode_quantized_mesh(file_bytes(files[f].path));
    worst = std::max(worst, check_against_brute_force(m, 257, 300, rng, files[f].path.string()));
    worst = std::max(worst, check_against_brute_force(m, 65, 100, rng, files[f].path.string()));
    ++meshes;
  }
  const QuantizedMesh big =
      decode_quantized_mesh(file_bytes(tile_files(fixtures() / "mercator-qm").back().path));
  // Web mercator rows (v linear in latitude): the tile's own rows.
  const TileFile last = tile_files(fixtures() / "mercator-qm").back();
  const std::vector<double> rows =
      globe::viewer::mercator_row_v(last.z, (1u << last.z) - 1 - last.y_tms, 257);
  worst = std::max(worst, check_against_brute_force(big, 257, 20, rng, "mercator 257", rows));
  const QuantizedMesh dense = decoded(lattice_mesh(9, 99, 0.0, 0));
  for (int z = 0; z < 12; z += 5)
    worst = std::max(worst, check_against_brute_force(dense, 65, 300, rng, "mercator rows",
                                                      globe::viewer::mercator_row_v(z, 0, 65)));
  for (uint32_t seed = 1; seed <= 12; ++seed) {
    const TestMesh t = lattice_mesh(3 + int(seed % 5) * 4, seed, seed % 3 ? 0.15 : 0.0, 4);
    const QuantizedMesh m = decoded(t);
    for (const int size : {2, 33, 65, 257})
      worst = std::max(
          worst, check_against_brute_force(m, size, 400, rng, "lattice " + std::to_string(seed)));
    ++meshes;
  }
  // A mesh with no triangles, or only degenerate ones, is all holes.
  TestMesh flat = lattice_mesh(3, 5, 1.0, 2);
  for (float h : mesh_grid(decoded(flat), 17))
    EXPECT_TRUE(std::isnan(h));
  std::cerr << meshes << " meshes: largest difference from the brute force " << worst << " m\n";
}

// (c) Two tiles whose edge vertices agree give bit-identical edge samples,
// whatever their interiors and the block size.
TEST(QuantizedMeshReader, NeighboursWithAgreeingEdgesGiveIdenticalEdgeSamples) {
  std::mt19937 rng(3);
  auto positions = [&](int n) {
    std::set<uint16_t> s;
    while (int(s.size()) < n)
      s.insert(uint16_t(1 + rng() % (qm::kQuantizedMax - 1)));
    return std::vector<uint16_t>(s.begin(), s.end());
  };
  // Heights a function of the position along the shared edges only.
  auto height = [](int u, int v) { return uint16_t((u * 7 + v * 13 + (u ^ v)) % 32768); };
  for (int round = 0; round < 10; ++round) {
    const std::vector<uint16_t> shared_v = positions(3 + round * 5),
                                shared_u = positions(4 + round);
    // A west of B; A north of C.
    const TestMesh a = fan_mesh(positions(3), positions(7), shared_v, positions(2),
                                uint16_t(2000 + rng() % 28000), uint16_t(2000 + rng() % 28000),
                                [&](int u, int v) { return height(u == 32767 ? 0 : u, v); });
    const TestMesh b =
        fan_mesh(shared_v, positions(5), positions(9), positions(1), uint16_t(2000 + rng() % 28000),
                 uint16_t(2000 + rng() % 28000), height);
    TestMesh a2 = fan_mesh(positions(3), shared_u, positions(4), positions(2), 16000, 9000,
                           [&](int u, int v) { return height(u, v == 0 ? 32767 : v); });
    const TestMesh c =
        fan_mesh(positions(2), positions(6), positions(3), shared_u, 9000, 16000, height);
    const QuantizedMesh ma = decoded(a), mb = decoded(b), ma2 = decoded(a2), mc = decoded(c);
    for (const int size : {17, 65, 129, 257}) {
      const std::vector<float> ga = mesh_grid(ma, size), gb = mesh_grid(mb, size),
                               ga2 = mesh_grid(ma2, size), gc = mesh_grid(mc, size);
      const size_t n = size_t(size), last = n - 1;
      for (size_t j = 0; j < n; ++j)
        ASSERT_EQ(std::bit_cast<uint32_t>(ga[j * n + last]), std::bit_cast<uint32_t>(gb[j * n]))
            << "round " << round << " size " << size << " row " << j;
      for (size_t i = 0; i < n; ++i)
        ASSERT_EQ(std::bit_cast<uint32_t>(ga2[last * n + i]), std::bit_cast<uint32_t>(gc[i]))
            << "round " << round << " size " << size << " column " << i;
    }
  }
}

// (c) Exported neighbours cut the same edge vertices, each tile quantizing
// its heights alone: their own edge samples agree within both quanta.
TEST(QuantizedMeshReader, ExportedNeighboursEdgeSamplesAgreeWithinTheirQuanta) {
  std::map<std::tuple<int, uint32_t, uint32_t>, QuantizedMesh> tiles;
  for (const TileFile& f : tile_files(fixtures() / "geodetic-qm"))
    if (f.z == 3) tiles[{f.z, f.x, f.y_tms}] = decode_quantized_mesh(file_bytes(f.path));
  ASSERT_EQ(tiles.size(), 128u);
  const int n = 65;
  auto quantum = [](const QuantizedMesh& m) {
    return (double(m.header.max_height) - m.header.min_height) / qm::kQuantizedMax;
  };
  double worst = 0;
  for (const auto& [k, m] : tiles) {
    const auto [z, x, y] = k;
    const auto east = tiles.find({z, (x + 1) % 16, y});  // wraps the antimeridian
    const std::vector<float> g = mesh_grid(m, n);
    if (east != tiles.end()) {
      const std::vector<float> e = mesh_grid(east->second, n);
      const double bound = (quantum(m) + quantum(east->second)) / 2 + 1e-3;
      for (int j = 0; j < n; ++j) {
        const double d = std::abs(double(g[size_t(j * n + n - 1)]) - e[size_t(j * n)]);
        worst = std::max(worst, d);
        EXPECT_LE(d, bound) << x << "/" << y << " east edge row " << j;
      }
    }
    const auto north = tiles.find({z, x, y + 1});
    if (north != tiles.end()) {
      const std::vector<float> s = mesh_grid(north->second, n);
      const double bound = (quantum(m) + quantum(north->second)) / 2 + 1e-3;
      for (int i = 0; i < n; ++i) {
        const double d = std::abs(double(g[size_t(i)]) - s[size_t((n - 1) * n + i)]);
        worst = std::max(worst, d);
        EXPECT_LE(d, bound) << x << "/" << y << " north edge column " << i;
      }
    }
  }
  std::cerr << "exported neighbours' own edge samples: largest difference " << worst << " m\n";
}

// (d) Broken tiles throw FormatError, never crash (the ASan build runs this
// too): every truncated prefix, gzip truncated, each count too large, index
// codes and indices out of range, coordinates out of range, bad headers and
// extensions, and 2,000 random byte changes (what decodes then samples).
TEST(QuantizedMeshReader, MalformedTilesThrowFormatError) {
  auto rejects = [](const Bytes& b) {
    try {
      decode_quantized_mesh(b);
      return false;
    } catch (const tileformat::FormatError&) {
      return true;
    }
  };
  TestMesh t = lattice_mesh(6, 1, 0.0, 0);
  t.extensions = {{1, Bytes(2 * t.u.size(), 0x80)}, {9, Bytes{7, 7}}};
  const Bytes good = write_mesh(t);
  const size_t n = t.u.size();
  ASSERT_FALSE(rejects(good));
  // Prefixes: all rejected but those ending where an extension begins (a
  // tile without it, which is valid).
  const size_t end_of_edges = good.size() - (5 + 2 * n) - (5 + 2);
  for (size_t len = 0; len < good.size(); ++len) {
    const Bytes prefix(good.begin(), good.begin() + long(len));
    const bool boundary = len == end_of_edges || len == end_of_edges + 5 + 2 * n;
    EXPECT_EQ(rejects(prefix), !boundary) << "prefix of " << len << " bytes";
  }
  // The same for a gzipped export and a 32-bit tile (a sample of prefixes).
  const Bytes gz = file_bytes(tile_files(fixtures() / "geodetic-gz").back().path);
  for (size_t len = 0; len < gz.size(); len += 1 + len / 50)
    EXPECT_TRUE(rejects(Bytes(gz.begin(), gz.begin() + long(len)))) << "gzip prefix " << len;
  const Bytes wide = write_mesh(lattice_mesh(259, 2, 0.0, 0));
  for (size_t len = 0; len < wide.size(); len += 1 + len / 20)
    EXPECT_TRUE(rejects(Bytes(wide.begin(), wide.begin() + long(len)))) << "32-bit prefix " << len;

  auto patched = [&](size_t at, uint32_t value) {
    Bytes b = good;
    for (int i = 0; i < 4; ++i)
      b[at + size_t(i)] = uint8_t(value >> (8 * i));
    return b;
  };
  const size_t triangles_at = 88 + 4 + 6 * n;
  const size_t indices_at = triangles_at + 4;
  const size_t edges_at = indices_at + 2 * t.tris.size();
  EXPECT_TRUE(rejects(patched(88, 0xffffffffu))) << "vertex count";
  EXPECT_TRUE(rejects(patched(88, uint32_t(n + 1)))) << "vertex count one more";
  EXPECT_TRUE(rejects(patched(triangles_at, 0x7fffffffu))) << "triangle count";
  EXPECT_TRUE(rejects(patched(edges_at, 0x40000000u))) << "west edge count";
  EXPECT_TRUE(rejects(patched(edges_at + 4, 0xffffu))) << "west edge index";
  {  // an index code above the high-water mark
    Bytes b = good;
    b[indices_at] = 5;
    EXPECT_TRUE(rejects(b));
  }
  {  // new vertices beyond the vertex count
    TestMesh few;
    few.u = {0, 100, 0};
    few.v = {0, 0, 100};
    few.h = {0, 0, 0};
    few.codes = {0, 0, 0, 0, 1, 3};  // vertices 0 1 2, then 3 2 0
    EXPECT_TRUE(rejects(write_mesh(few)));
    few.codes = {0, 0, 0, 3, 2, 1};  // 0 1 2, 0 1 2: fine
    EXPECT_FALSE(rejects(write_mesh(few)));
  }
  {  // u past 32767 by its deltas
    Bytes b = good;
    b[92] = 0xfe;  // zig-zag 0xfffe: +32767
    b[93] = 0xff;
    b[94] = 0xfe;
    b[95] = 0xff;
    EXPECT_TRUE(rejects(b));
    b[92] = 0x01;  // -1
    b[93] = 0x00;
    EXPECT_TRUE(rejects(b));
  }
  {  // heights: not finite, min above max
    TestMesh h = t;
    h.min_h = std::numeric_limits<float>::quiet_NaN();
    EXPECT_TRUE(rejects(write_mesh(h)));
    h.min_h = 10;
    h.max_h = 5;
    EXPECT_TRUE(rejects(write_mesh(h)));
    h.min_h = -std::numeric_limits<float>::infinity();
    EXPECT_TRUE(rejects(write_mesh(h)));
  }
  {  // extensions: normals of the wrong length, water mask of the wrong
     // size, metadata longer than its extension, a length past the end
    TestMesh e = t;
    e.extensions = {{1, Bytes(2 * n - 2, 0)}};
    EXPECT_TRUE(rejects(write_mesh(e)));
    e.extensions = {{2, Bytes(100, 0)}};
    EXPECT_TRUE(rejects(write_mesh(e)));
    Bytes meta;
    put_u32(meta, 50);
    e.extensions = {{4, meta}};
    EXPECT_TRUE(rejects(write_mesh(e)));
    Bytes b = good;
    b[end_of_edges + 1] = 0xff;
    EXPECT_TRUE(rejects(b));
  }
  {  // gzip: broken, trailing bytes, empty
    Bytes b = gz;
    b[b.size() / 2] ^= 0x55;
    EXPECT_TRUE(rejects(b));
    b = gz;
    b.push_back(0);
    b.push_back(1);
    b.push_back(2);
    EXPECT_TRUE(rejects(b));
    EXPECT_TRUE(rejects(Bytes{0x1f, 0x8b}));
    EXPECT_TRUE(rejects(Bytes{}));
  }
  // Random changes: decoded or rejected, and what decodes samples anyway.
  std::mt19937 rng(17);
  int decoded_count = 0;
  for (int k = 0; k < 2000; ++k) {
    Bytes b = good;
    for (int c = 0; c < 1 + k % 4; ++c)
      b[rng() % b.size()] = uint8_t(rng());
    try {
      const QuantizedMesh m = decode_quantized_mesh(b);
      ++decoded_count;
      for (float h : mesh_grid(m, 33))
        ASSERT_TRUE(std::isnan(h) || std::isfinite(h));
    } catch (const tileformat::FormatError&) {
    }
  }
  std::cerr << decoded_count << " of 2000 changed tiles still decode\n";
}

// ------------------------------------------------- the reader over HTTP ----

globe::net::ClientOptions quiet_client() {
  globe::net::ClientOptions o;
  o.max_retries = 1;
  o.backoff_initial_s = 0.01;
  o.log = [](const std::string&) {};
  return o;
}

// CesiumJS's level error (docs/web.md): a quarter of the equator / (65 *
// roots across) / 2^z.
double level_error(int z, int roots_across) {
  return 6378137.0 * 2 * qm::kPi / 4 / (65.0 * roots_across) / std::ldexp(1.0, z);
}

// Per zoom, the largest and the 99th percentile of |reader - package|.
using ZoomStats = std::map<int, std::pair<double, double>>;
struct BlockCheck {
  ZoomStats samples;  // the reader's samples(): each tile's own mesh
  ZoomStats blocks;   // its blobs (BlockSynthesizer: nested in their parents)
};

// Every block the reader makes of `ids` against the package's block of the
// same tile, at the package's samples.
// - samples(), the heights the reader gives the synthesizer: within the
//   export's error (the finest zoom: --finest-error 2 m; coarser: the
//   level's error, docs/web.md) plus the quantizations (the tiles' heights,
//   the package's step) and the slope over half a u and half a v unit
//   (vertices are rounded to whole units).
// - tile(), the blob: the same plus the blob's step, with the error of the
//   zoom the sample comes from (BlockSynthesizer nests a block's samples at
//   its parent's positions in the parent's block: a sample at global
//   position (gx, gy) of zoom z comes from zoom z - k, k the trailing zero
//   bits both share); shared edges of neighbouring blocks identical.
BlockCheck check_blocks(QuantizedMeshReader& reader, tileformat::PackageReader& pkg,
                        const std::vector<TileId>& ids, int finest, double max_quantum) {
  const tileformat::TerrainMetadata meta = tileformat::read_terrain_metadata(pkg.metadata());
  const tileformat::Tiling& tiling = meta.common.tiling;
  std::map<TileId, tileformat::MBlock> mine;
  std::map<int, Stats> sample_stats, block_stats;
  for (const TileId& id : ids) {
    const std::optional<Bytes> blob = reader.tile(id);
    const std::optional<std::vector<float>> own = reader.samples(id);
    const std::optional<Bytes> want = pkg.tile(id);
    EXPECT_EQ(blob.has_value(), want.has_value()) << id.str();
    if (!blob || !want || !own) continue;
    const tileformat::MBlock got = tileformat::decode_mblock(*blob);
    const tileformat::MBlock ref = tileformat::decode_mblock(*want);
    EXPECT_EQ(got.size, QuantizedMeshReader::kBlockSize);
    EXPECT_EQ(got.step, QuantizedMeshReader::kHeightStep);
    const int scale = (got.size - 1) / (ref.size - 1);
    // v units between the package's rows: even in latitude (geodetic), or
    // not (web mercator: rows even in mercator y, v linear in latitude).
    std::vector<double> row_v(size_t(ref.size));
    for (int j = 0; j < ref.size; ++j) {
      if (tiling.scheme != tileformat::Scheme::kWebMercator) {
        row_v[size_t(j)] = double(ref.size - 1 - j) / (ref.size - 1) * qm::kQuantizedMax;
        continue;
      }
      const double n = std::ldexp(1.0, id.z);
      auto lat = [&](double row) { return std::atan(std::sinh(qm::kPi * (1 - 2 * row / n))); };
      const double north = lat(id.y), south = lat(id.y + 1.0);
      row_v[size_t(j)] =
          (lat(id.y + double(j) / (ref.size - 1)) - south) / (north - south) * qm::kQuantizedMax;
    }
    const double units_per_column = double(qm::kQuantizedMax) / (ref.size - 1);
    auto zoom_error = [&](int z) { return z == finest ? 2.0 : level_error(z, tiling.roots_x); };
    for (int j = 0; j < ref.size; ++j)
      for (int i = 0; i < ref.size; ++i) {
        const double h = ref.height(i, j);
        // Vertices lie within half a u and half a v unit of their sample:
        // the steepest change per unit between neighbouring samples around
        // this one, along each axis, times half a unit.
        double slope_u = 0, slope_v = 0;
        for (int nj = std::max(j - 1, 0); nj <= std::min(j + 1, ref.size - 1); ++nj)
          for (int ni = std::max(i - 1, 0); ni <= std::min(i + 1, ref.size - 1); ++ni) {
            if (ni + 1 < ref.size)
              slope_u = std::max(slope_u, std::abs(ref.height(ni + 1, nj) - ref.height(ni, nj)) /
                                              units_per_column);
            if (nj + 1 < ref.size)
              slope_v = std::max(slope_v, std::abs(ref.height(ni, nj + 1) - ref.height(ni, nj)) /
                                              (row_v[size_t(nj)] - row_v[size_t(nj + 1)]));
          }
        const double margin = max_quantum / 2 + ref.step / 2 + (slope_u + slope_v) * 0.5 + 1e-3;
        const size_t at = size_t(j * scale) * size_t(got.size) + size_t(i * scale);
        const double d_own = std::abs((*own)[at] - h);
        sample_stats[id.z].add(d_own);
        EXPECT_LE(d_own, zoom_error(id.z) + margin)
            << id.str() << " sample (" << i << ", " << j << ") of samples()";
        // The zoom the blob's sample comes from.
        const uint64_t gx = uint64_t(id.x) * uint64_t(got.size - 1) + uint64_t(i * scale);
        const uint64_t gy = uint64_t(id.y) * uint64_t(got.size - 1) + uint64_t(j * scale);
        int from = id.z;
        while (from > 0 && (gx >> (id.z - from)) % 2 == 0 && (gy >> (id.z - from)) % 2 == 0)
          --from;
        if (!got.is_valid(i * scale, j * scale)) {
          ADD_FAILURE() << id.str() << " sample (" << i << ", " << j << ") is a hole";
          continue;
        }
        const double d = std::abs(got.height(i * scale, j * scale) - h);
        block_stats[id.z].add(d);
        EXPECT_LE(d, zoom_error(from) + margin + got.step / 2)
            << id.str() << " sample (" << i << ", " << j << ") of the blob, from zoom " << from;
      }
    mine[id] = got;
  }
  // Shared edges: identical quantized heights (the owner's samples).
  size_t edges = 0;
  for (const auto& [id, b] : mine) {
    const int last = b.size - 1;
    const TileId east{id.z, uint32_t((id.x + 1) % tiling.tiles_x(id.z)), id.y};
    if (const auto e = mine.find(east); e != mine.end() && east != id) {
      ++edges;
      for (int j = 0; j <= last; ++j)
        if (b.q[size_t(j * b.size + last)] != e->second.q[size_t(j * b.size)]) {
          ADD_FAILURE() << id.str() << " east edge row " << j << ": "
                        << b.q[size_t(j * b.size + last)] << " here, "
                        << e->second.q[size_t(j * b.size)] << " in " << east.str();
          break;
        }
    }
    const TileId south{id.z, id.x, id.y + 1};
    if (const auto s = mine.find(south); s != mine.end()) {
      ++edges;
      for (int i = 0; i <= last; ++i)
        if (b.q[size_t(last * b.size + i)] != s->second.q[size_t(i)]) {
          ADD_FAILURE() << id.str() << " south edge column " << i << ": "
                        << b.q[size_t(last * b.size + i)] << " here, " << s->second.q[size_t(i)]
                        << " in " << south.str();
          break;
        }
    }
  }
  EXPECT_GT(edges, mine.size() / 2);
  BlockCheck out;
  for (const auto& [z, s] : sample_stats) {
    out.samples[z] = {s.max(), s.p99()};
    const Stats& b = block_stats[z];
    out.blocks[z] = {b.max(), b.p99()};
    std::cerr << "zoom " << z << ": " << s.d.size()
              << " package samples; |samples() - package| max " << s.max() << " m, p99 " << s.p99()
              << " m; |blob - package| max " << b.max() << " m, p99 " << b.p99() << " m\n";
  }
  return out;
}

double largest_quantum(const fs::path& folder) {
  double q = 0;
  for (const TileFile& f : tile_files(folder)) {
    const QuantizedMesh m = decode_quantized_mesh(file_bytes(f.path));
    q = std::max(q, (double(m.header.max_height) - m.header.min_height) / qm::kQuantizedMax);
  }
  return q;
}

// (e) The gzipped export served as files (bodies gzip without
// Content-Encoding; `?v=` queries the server ignores): every block of every
// zoom against the package, shared edges identical (the antimeridian too),
// and no request for a tile the layer.json does not list.
TEST(QuantizedMeshReader, BlocksFromAServedFolderMatchThePackage) {
  const fs::path folder = fixtures() / "geodetic-gz";
  TempDir dir;
  FaultServer server(folder, {}, dir.path());
  ASSERT_GT(server.port(), 0);
  globe::net::HttpClient client(quiet_client());
  QuantizedMeshReader reader(server.url("/layer.json"), client);
  const tileformat::TerrainMetadata meta = tileformat::read_terrain_metadata(reader.metadata());
  EXPECT_EQ(meta.common.tiling.scheme, tileformat::Scheme::kGeodetic);
  EXPECT_EQ(meta.block_size, QuantizedMeshReader::kBlockSize);
  EXPECT_EQ(meta.height_step, QuantizedMeshReader::kHeightStep);
  EXPECT_EQ(meta.common.min_zoom, 0);
  EXPECT_EQ(meta.common.max_zoom, 3);
  EXPECT_EQ(reader.tile_url({3, 5, 0}), server.url("/3/5/7.terrain?v=1.0.0"));

  tileformat::PackageReader pkg((fixtures() / "geodetic.mbtiles").string());
  std::vector<TileId> ids;
  for (int z = 0; z <= 3; ++z) {
    const std::vector<TileId> want = pkg.tile_ids(z);
    EXPECT_EQ(reader.tile_ids(z), want) << "zoom " << z;
    for (const TileId& id : want)
      EXPECT_TRUE(reader.has_tile(id));
    ids.insert(ids.end(), want.begin(), want.end());
  }
  EXPECT_FALSE(reader.has_tile({4, 0, 0}));
  EXPECT_FALSE(reader.tile({4, 0, 0}).has_value());
  reader.prefetch(ids);
  const BlockCheck stats = check_blocks(reader, pkg, ids, 3, largest_quantum(folder));
  EXPECT_TRUE(stats.samples.count(3));
  server.stop();
  for (const LogEntry& e : server.log()) {
    EXPECT_EQ(e.status, 200) << e.path;
    if (e.path == "/layer.json") continue;
    EXPECT_NE(e.path.find(".terrain"), std::string::npos) << e.path;
  }
  EXPECT_EQ(client.stats().no_content, 0u);
}

// (e) A layer.json that lists part of zoom 3 (and a query every tile
// request carries on): those tiles are all there is, nothing else is asked
// for, and blocks at the listed area's rim keep their own edges.
TEST(QuantizedMeshReader, OnlyListedTilesAreEverRequested) {
  TempDir dir;
  const fs::path src = fixtures() / "geodetic-qm";
  const fs::path root = dir / "root";
  fs::create_directories(root);
  for (const char* z : {"0", "1", "2", "3"})
    fs::create_directory_symlink(src / z, root / z);
  std::string layer = read_file(src / "layer.json");
  const size_t at = layer.find("\"available\"");
  ASSERT_NE(at, std::string::npos);
  layer = layer.substr(0, at) + R"("available": [
    [{"startX": 0, "startY": 0, "endX": 1, "endY": 0}],
    [{"startX": 0, "startY": 0, "endX": 3, "endY": 1}],
    [{"startX": 0, "startY": 0, "endX": 7, "endY": 3}],
    [{"startX": 4, "startY": 4, "endX": 7, "endY": 6}, {"startX": 15, "startY": 0, "endX": 15, "endY": 0}]
  ]
})";
  std::ofstream(root / "layer.json") << layer;
  FaultServer server(root, {}, dir.path());
  ASSERT_GT(server.port(), 0);
  globe::net::HttpClient client(quiet_client());
  QuantizedMeshReader reader(server.url("/layer.json?token=abc"), client);
  EXPECT_EQ(reader.tile_url({3, 4, 1}), server.url("/3/4/6.terrain?v=1.0.0&token=abc"));
  std::set<std::string> listed;
  std::vector<TileId> want;
  for (uint32_t tms_y = 4; tms_y <= 6; ++tms_y)
    for (uint32_t x = 4; x <= 7; ++x) {
      want.push_back({3, x, 7 - tms_y});
      listed.insert("/3/" + std::to_string(x) + "/" + std::to_string(tms_y) + ".terrain");
    }
  want.push_back({3, 15, 7});
  listed.insert("/3/15/0.terrain");
  for (int z = 0; z <= 2; ++z)  // zooms 0-2: every tile (the blocks' ancestors)
    for (uint32_t y = 0; y < (1u << z); ++y)
      for (uint32_t x = 0; x < (2u << z); ++x)
        listed.insert("/" + std::to_string(z) + "/" + std::to_string(x) + "/" + std::to_string(y) +
                      ".terrain");
  std::sort(want.begin(), want.end(), [](const TileId& a, const TileId& b) {
    return std::tie(a.y, a.x) < std::tie(b.y, b.x);
  });
  EXPECT_EQ(reader.tile_ids(3), want);
  for (uint32_t y = 0; y < 8; ++y)
    for (uint32_t x = 0; x < 16; ++x) {
      const bool in = std::find(want.begin(), want.end(), TileId{3, x, y}) != want.end();
      EXPECT_EQ(reader.has_tile({3, x, y}), in) << x << "/" << y;
      if (!in) {
        EXPECT_FALSE(reader.tile({3, x, y}).has_value());
      }
    }
  tileformat::PackageReader pkg((fixtures() / "geodetic.mbtiles").string());
  check_blocks(reader, pkg, want, 3, largest_quantum(src));
  server.stop();
  std::set<std::string> asked;
  for (const LogEntry& e : server.log()) {
    if (e.path == "/layer.json") continue;
    EXPECT_TRUE(listed.count(e.path)) << "asked for an unlisted tile: " << e.path;
    EXPECT_TRUE(asked.insert(e.path).second) << "asked twice: " << e.path;
  }
  for (uint32_t tms_y = 4; tms_y <= 6; ++tms_y)  // each listed tile of zoom 3 once
    for (uint32_t x = 4; x <= 7; ++x)
      EXPECT_TRUE(
          asked.count("/3/" + std::to_string(x) + "/" + std::to_string(tms_y) + ".terrain"));
}

// (e) globe-serve cutting the tiles on the fly (web mercator, 257² blocks,
// 32-bit indices, gzip by Content-Encoding): the blocks are the package's
// within the export's error.
TEST(QuantizedMeshReader, BlocksFromGlobeServeMatchThePackage) {
  TempDir dir;
  ServeProcess serve({"-q", (fixtures() / "mercator.mbtiles").string()}, dir.path());
  ASSERT_GT(serve.port(), 0) << serve.log();
  globe::net::HttpClient client(quiet_client());
  const std::string base = "http://127.0.0.1:" + std::to_string(serve.port());
  QuantizedMeshReader reader(base + "/mercator/layer.json", client);
  EXPECT_EQ(reader.tiling().scheme, tileformat::Scheme::kWebMercator);
  tileformat::PackageReader pkg((fixtures() / "mercator.mbtiles").string());
  std::vector<TileId> ids;
  for (int z = 0; z <= 1; ++z)
    for (const TileId& id : pkg.tile_ids(z))
      ids.push_back(id);
  ASSERT_EQ(ids.size(), 5u);
  const BlockCheck stats =
      check_blocks(reader, pkg, ids, 1, largest_quantum(fixtures() / "mercator-qm"));
  EXPECT_TRUE(stats.samples.count(1));
  EXPECT_EQ(client.stats().no_content, 0u);
}

// Loader threads at once, with batches asked for and forgotten under them:
// the same blobs, byte for byte, as one thread asking one tile at a time.
TEST(QuantizedMeshReader, ConcurrentTilesAndForgottenPrefetchesGiveTheSameBlobs) {
  const fs::path folder = fixtures() / "geodetic-qm";
  TempDir dir;
  FaultServer server(folder, {}, dir.path());
  ASSERT_GT(server.port(), 0);
  globe::net::HttpClient client(quiet_client());
  std::vector<TileId> ids;
  std::map<TileId, Bytes> want;
  {
    QuantizedMeshReader reader(server.url("/layer.json"), client);
    ids = reader.tile_ids(2);
    for (const TileId& id : ids)
      want[id] = reader.tile(id).value();
  }
  QuantizedMeshReader reader(server.url("/layer.json"), client);
  reader.prefetch(ids);
  reader.forget(std::span(ids).first(ids.size() / 2));
  std::vector<std::map<TileId, Bytes>> got(4);
  std::vector<std::string> errors(4);
  std::vector<std::thread> threads;
  for (size_t t = 0; t < 4; ++t)
    threads.emplace_back([&, t] {
      try {
        for (size_t k = 0; k < ids.size() / 2; ++k) {  // overlapping halves
          const TileId id = ids[(k * 7 + t * 13) % ids.size()];
          if (k % 5 == t) reader.forget(std::span(&id, 1));
          got[t][id] = reader.tile(id).value();
        }
      } catch (const std::exception& e) {
        errors[t] = e.what();
      }
    });
  for (std::thread& t : threads)
    t.join();
  for (size_t t = 0; t < 4; ++t) {
    EXPECT_EQ(errors[t], "") << "thread " << t;
    for (const auto& [id, blob] : got[t])
      EXPECT_TRUE(blob == want.at(id)) << "thread " << t << " tile " << id.str();
  }
}

// A layer.json the reader cannot use says why, naming the URL.
TEST(QuantizedMeshReader, UnusableLayerJsonIsAnInputError) {
  TempDir dir;
  const fs::path root = dir / "root";
  fs::create_directories(root);
  const std::map<std::string, std::string> cases = {
      {"heightmap.json", R"({"format": "heightmap-1.0", "tiles": ["{z}/{x}/{y}.terrain"]})"},
      {"swiss.json",
       R"({"format": "quantized-mesh-1.0", "projection": "EPSG:2056", "tiles": ["a"]})"},
      {"xyz.json", R"({"format": "quantized-mesh-1.0", "scheme": "xyz", "tiles": ["a"]})"},
      {"no_tiles.json", R"({"format": "quantized-mesh-1.0", "maxzoom": 3})"},
      {"bad_available.json",
       R"({"format": "quantized-mesh-1.0", "tiles": ["a"], "available": [[{"startX": -1}]]})"},
      {"not_json.json", "<html>"}};
  for (const auto& [name, text] : cases)
    std::ofstream(root / name) << text;
  FaultServer server(root, {}, dir.path());
  ASSERT_GT(server.port(), 0);
  globe::net::HttpClient client(quiet_client());
  for (const auto& [name, text] : cases) {
    const std::string url = server.url("/" + name);
    try {
      QuantizedMeshReader reader(url, client);
      ADD_FAILURE() << name << " was accepted";
    } catch (const globe::InputError& e) {
      EXPECT_NE(std::string(e.what()).find(url), std::string::npos) << e.what();
    }
  }
  EXPECT_THROW(QuantizedMeshReader(server.url("/missing.json"), client), globe::InputError);
}

}  // namespace
