// Helpers of the quantized-mesh tests: an exported folder read with the
// decoder written from the specification (spec_readers/), tile rectangles as
// CesiumJS defines them, and heights interpolated in a tile's triangles the
// way CesiumJS samples terrain (barycentric in u, v). Nothing here shares
// code with the exporter.
#pragma once

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include "spec_readers/quantized_mesh_reader.hpp"
#include "test_support.hpp"

namespace globe_test {

namespace qm = spec_readers::quantized_mesh;

struct MeshTile {
  int z = 0;
  uint32_t x = 0, y = 0;  // y: TMS row, from the south
  qm::Rectangle rect;     // degrees
  qm::Mesh mesh;
  double quantum() const {  // metres per height unit
    return (double(mesh.header.max_height) - mesh.header.min_height) / qm::kQuantizedMax;
  }
  double vertex_height(size_t k) const {
    return mesh.header.min_height + quantum() * mesh.height[k];
  }
  double vertex_lon(size_t k) const {
    return rect.west + (rect.east - rect.west) * mesh.u[k] / double(qm::kQuantizedMax);
  }
  double vertex_lat(size_t k) const {
    return rect.south + (rect.north - rect.south) * mesh.v[k] / double(qm::kQuantizedMax);
  }
};
using MeshTiles = std::map<std::tuple<int, uint32_t, uint32_t>, MeshTile>;

// CesiumJS's WebMercatorTilingScheme: one root, rows here from the south.
inline qm::Rectangle mercator_tile_rectangle(int z, uint32_t x, uint32_t y_tms) {
  const double n = std::ldexp(1.0, z);
  auto lat = [&](double row_from_north) {
    return std::atan(std::sinh(qm::kPi * (1 - 2 * row_from_north / n))) * 180 / qm::kPi;
  };
  const double row = n - 1 - y_tms;
  return {x / n * 360 - 180, lat(row + 1), (x + 1) / n * 360 - 180, lat(row)};
}

// Every DIR/{z}/{x}/{y}.terrain, decoded (a tile that does not decode fails
// the test that reads it).
inline MeshTiles read_mesh_folder(const fs::path& dir, bool mercator) {
  MeshTiles tiles;
  for (const auto& entry : fs::recursive_directory_iterator(dir)) {
    if (entry.path().extension() != ".terrain") continue;
    const fs::path rel = fs::relative(entry.path(), dir);
    auto it = rel.begin();
    MeshTile t;
    t.z = std::stoi((it++)->string());
    t.x = uint32_t(std::stoul((it++)->string()));
    t.y = uint32_t(std::stoul(it->stem().string()));
    t.rect = mercator ? mercator_tile_rectangle(t.z, t.x, t.y)
                      : qm::geographic_tile_rectangle(t.z, t.x, t.y);
    try {
      t.mesh = qm::decode(read_file(entry.path()));
      qm::validate_mesh(t.mesh);
    } catch (const std::exception& e) {
      ADD_FAILURE() << entry.path() << ": " << e.what();
      continue;
    }
    tiles[{t.z, t.x, t.y}] = std::move(t);
  }
  return tiles;
}

// The triangles of a tile bucketed by a grid over (u, v), for lookups.
struct TriangleIndex {
  static constexpr int kCells = 32;
  std::vector<std::vector<uint32_t>> cells;  // triangle numbers per cell
  explicit TriangleIndex(const qm::Mesh& m) : cells(kCells * kCells) {
    auto cell = [](double q) {
      return std::min(kCells - 1, int(q * kCells / (qm::kQuantizedMax + 1.0)));
    };
    for (uint32_t k = 0; k + 2 < m.triangles.size(); k += 3) {
      const uint32_t a = m.triangles[k], b = m.triangles[k + 1], c = m.triangles[k + 2];
      const int x0 = cell(std::min({m.u[a], m.u[b], m.u[c]})),
                x1 = cell(std::max({m.u[a], m.u[b], m.u[c]}));
      const int y0 = cell(std::min({m.v[a], m.v[b], m.v[c]})),
                y1 = cell(std::max({m.v[a], m.v[b], m.v[c]}));
      for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x)
          cells[size_t(y) * kCells + x].push_back(k / 3);
    }
  }
};

// The height of the tile's surface at (lon, lat), interpolated in the
// triangle containing it as CesiumJS does (in u, v), from `height(vertex)`;
// nullopt outside every triangle.
inline std::optional<double> mesh_height_at(const MeshTile& t, double lon, double lat,
                                            const std::function<double(size_t)>& height,
                                            const TriangleIndex* index = nullptr) {
  const double u = (lon - t.rect.west) / (t.rect.east - t.rect.west) * qm::kQuantizedMax;
  const double v = (lat - t.rect.south) / (t.rect.north - t.rect.south) * qm::kQuantizedMax;
  const qm::Mesh& m = t.mesh;
  auto try_triangle = [&](size_t k) -> std::optional<double> {
    const uint32_t a = m.triangles[k], b = m.triangles[k + 1], c = m.triangles[k + 2];
    const double ax = m.u[a], ay = m.v[a], bx = m.u[b], by = m.v[b], cx = m.u[c], cy = m.v[c];
    const double area = (bx - ax) * (cy - ay) - (by - ay) * (cx - ax);
    if (area == 0) return std::nullopt;
    const double wa = ((bx - u) * (cy - v) - (by - v) * (cx - u)) / area;
    const double wb = ((cx - u) * (ay - v) - (cy - v) * (ax - u)) / area;
    const double wc = 1 - wa - wb;
    const double eps = -1e-9;
    if (wa < eps || wb < eps || wc < eps) return std::nullopt;
    return wa * height(a) + wb * height(b) + wc * height(c);
  };
  if (index) {
    const int x = std::clamp(int(u * TriangleIndex::kCells / (qm::kQuantizedMax + 1.0)), 0,
                             TriangleIndex::kCells - 1);
    const int y = std::clamp(int(v * TriangleIndex::kCells / (qm::kQuantizedMax + 1.0)), 0,
                             TriangleIndex::kCells - 1);
    for (uint32_t k : index->cells[size_t(y) * TriangleIndex::kCells + x])
      if (const auto h = try_triangle(size_t(k) * 3)) return h;
    return std::nullopt;
  }
  for (size_t k = 0; k + 2 < m.triangles.size(); k += 3)
    if (const auto h = try_triangle(k)) return h;
  return std::nullopt;
}

// The finest tile of `tiles` whose rectangle holds (lon, lat).
inline const MeshTile* finest_tile_at(const MeshTiles& tiles, double lon, double lat) {
  const MeshTile* best = nullptr;
  for (const auto& [_, t] : tiles)
    if (lon >= t.rect.west && lon <= t.rect.east && lat >= t.rect.south && lat <= t.rect.north &&
        (!best || t.z > best->z))
      best = &t;
  return best;
}

}  // namespace globe_test
