// Quantized-mesh tiles of a terrain package (see mesh_tiles.hpp).
#include "web/mesh_tiles.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>

#include "tileformat/json.hpp"
#include "tileformat/mblock.hpp"
#include "web/quantized_mesh.hpp"
#include "web/raster_dem.hpp"

namespace globe::web {
namespace {

using tileformat::TileId;

// Longitude and latitude of global sample (gx, gy) of zoom z with `steps`
// samples per tile edge: the same numbers in every tile that has the sample.
struct SampleGeometry {
  const tileformat::Tiling& tiling;
  int z, steps;
  void lonlat(int64_t gx, int64_t gy, double& lon, double& lat) const {
    const double spacing = tiling.tile_size(z) / steps;
    const double x = tiling.origin_x + double(gx) * spacing;
    const double y = tiling.origin_y - double(gy) * spacing;
    if (tiling.scheme == tileformat::Scheme::kWebMercator) {
      mercator_to_lonlat({x, y}, lon, lat);
    } else {
      lon = x, lat = std::clamp(y, -90.0, 90.0);
    }
    // One longitude for the antimeridian's two sides (-180 and 180 give
    // sines of opposite sign, which tips normals there differently).
    if (lon >= 180) lon -= 360;
    if (lon < -180) lon += 360;
  }
};

Vec3 sub(const Vec3& a, const Vec3& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double length(const Vec3& a) {
  return std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
}

// The longitudes and latitudes of one tile's sample columns and rows,
// apron included (index k is grid position k - 1): in both schemes a
// sample's longitude depends on its column only and its latitude on its row
// only, so their trigonometry is done n + 3 times, not per vertex.
struct TileFrame {
  std::vector<double> lon, lat;
  std::vector<EcefLongitude> lon_trig;
  std::vector<EcefLatitude> lat_trig;
  TileFrame(const SampleGeometry& geo, int64_t gx0, int64_t gy0) {
    const int n = geo.steps;
    for (int k = -1; k <= n + 1; ++k) {
      double lon_k, lat_k, unused;
      geo.lonlat(gx0 + k, gy0, lon_k, unused);
      geo.lonlat(gx0, gy0 + k, unused, lat_k);
      lon.push_back(lon_k), lat.push_back(lat_k);
      lon_trig.push_back(ecef_longitude(lon_k));
      lat_trig.push_back(ecef_latitude(lat_k));
    }
  }
  double lon_at(int i) const { return lon[size_t(i + 1)]; }
  double lat_at(int j) const { return lat[size_t(j + 1)]; }
  Vec3 position(int i, int j, double h) const {
    return ecef(lon_trig[size_t(i + 1)], lat_trig[size_t(j + 1)], h);
  }
};

// The vertex normal at grid point (i, j): central differences of the ECEF
// positions of the samples around it (one-sided where the apron has none);
// the ellipsoid's normal where they collapse (the poles).
Vec3 vertex_normal(const TileGrid& g, const TileFrame& frame, int i, int j) {
  auto position = [&](int a, int b) -> std::optional<Vec3> {
    const double h = g.at(a, b);
    if (std::isnan(h)) return std::nullopt;
    return frame.position(a, b, h);
  };
  const double lon = frame.lon_at(i), lat = frame.lat_at(j);
  if (std::fabs(lat) >= 90 - 1e-9) return {0, 0, lat > 0 ? 1.0 : -1.0};  // a pole
  const Vec3 centre = *position(i, j);
  const Vec3 east = sub(position(i + 1, j).value_or(centre), position(i - 1, j).value_or(centre));
  const Vec3 north = sub(position(i, j - 1).value_or(centre), position(i, j + 1).value_or(centre));
  Vec3 n = cross(east, north);
  const double len = length(n);
  if (len <= 1e-9 * std::max(1.0, length(east) * length(north)) || length(east) < 1e-6 ||
      length(north) < 1e-6)
    return ellipsoid_normal(lon, lat);
  return {n[0] / len, n[1] / len, n[2] / len};
}

}  // namespace

MeshTileSource::MeshTileSource(TerrainBlocks& blocks, OwnErrorCache& own_errors)
    : package_(blocks.package()), sampler_(blocks), own_errors_(own_errors) {}

std::optional<double> MeshTileSource::sample(int z, int64_t gx, int64_t gy) {
  const tileformat::Tiling& t = package_.tiling;
  const int steps = package_.block_size - 1;
  const int zs = std::max(z, package_.min_zoom);
  if (zs > package_.max_zoom) return std::nullopt;
  const int64_t f = int64_t{1} << (zs - z);
  gx *= f, gy *= f;
  const int64_t width = int64_t(t.tiles_x(zs)) * steps, height = int64_t(t.tiles_y(zs)) * steps;
  if (t.wraps_x()) gx = ((gx % width) + width) % width;
  if (gx < 0 || gy < 0 || gx > width || gy > height) return std::nullopt;
  // The sample's tile, or the tile before it where the sample is on its edge.
  const int64_t cols = int64_t(t.tiles_x(zs)), rows = int64_t(t.tiles_y(zs));
  for (int dy = 0; dy <= 1; ++dy)
    for (int dx = 0; dx <= 1; ++dx) {
      if ((dx && gx % steps != 0) || (dy && gy % steps != 0)) continue;
      const int64_t x0 = gx / steps - dx, ty = gy / steps - dy;  // x0 before wrapping
      const int64_t tx = t.wraps_x() ? (x0 % cols + cols) % cols : x0;
      if (tx < 0 || ty < 0 || tx >= cols || ty >= rows) continue;
      const tileformat::MBlock* b = sampler_.block({zs, uint32_t(tx), uint32_t(ty)});
      if (b) return b->height(int(gx - x0 * steps), int(gy - ty * steps));
    }
  return std::nullopt;
}

bool MeshTileSource::has_tile(TileId id) {
  return id.z == 0 || id.z < package_.min_zoom || sampler_.block(id) != nullptr;
}

std::shared_ptr<const std::vector<float>> MeshTileSource::own(TileId id, double limit) {
  const uint64_t key = tile_key(id);
  std::shared_ptr<const std::vector<float>> e;
  if (own_errors_.get(key, e)) return e;
  if (has_tile(id)) {
    const TileGrid g = grid(id);
    e = std::make_shared<const std::vector<float>>(
        own_errors(g, mesh_sample_metres(package_.tiling, id.z, g.steps), limit));
  }
  own_errors_.put(key, e, 64 + (e ? e->size() * sizeof(float) : 0));
  return e;
}

MeshErrors MeshTileSource::errors(TileId id, double threshold) {
  const tileformat::Tiling& t = package_.tiling;
  const int64_t cols = int64_t(t.tiles_x(id.z)), rows = int64_t(t.tiles_y(id.z));
  std::array<std::shared_ptr<const std::vector<float>>, 9> held;
  std::array<const std::vector<float>*, 9> around{};
  for (int k = 0; k < 9; ++k) {
    int64_t x = int64_t(id.x) + k % 3 - 1, y = int64_t(id.y) + k / 3 - 1;
    if (t.wraps_x()) x = (x % cols + cols) % cols;
    if (x < 0 || y < 0 || x >= cols || y >= rows) continue;
    held[size_t(k)] = own({id.z, uint32_t(x), uint32_t(y)}, threshold);
    around[size_t(k)] = held[size_t(k)].get();
  }
  return MeshErrors(package_.block_size - 1, int((id.x + id.y) & 1), around);
}

TileGrid MeshTileSource::grid(TileId id) {
  const int steps = package_.block_size - 1;
  TileGrid g(steps, int((id.x + id.y) & 1));
  const int64_t gx0 = int64_t(id.x) * steps, gy0 = int64_t(id.y) * steps;
  const int64_t rows = int64_t(package_.tiling.tiles_y(id.z)) * steps;
  const tileformat::MBlock* own = id.z >= package_.min_zoom ? sampler_.block(id) : nullptr;
  if (own) {  // the block itself, then the apron
    for (int j = 0; j <= steps; ++j)
      for (int i = 0; i <= steps; ++i)
        g.at(i, j) = own->height(i, j);
  }
  for (int j = -1; j <= steps + 1; ++j)
    for (int i = -1; i <= steps + 1; ++i) {
      const bool inside = i >= 0 && j >= 0 && i <= steps && j <= steps;
      if (own && inside) continue;
      const std::optional<double> h = sample(id.z, gx0 + i, gy0 + j);
      // Where every tile is exported (zoom 0, and below the package's
      // zooms) every sample of the Earth has a height, 0 m where no block
      // is, so that neighbours agree.
      const bool filled =
          (id.z < package_.min_zoom || id.z == 0) && gy0 + j >= 0 && gy0 + j <= rows;
      g.at(i, j) = h ? *h : filled || inside ? 0.0 : NAN;
    }
  return g;
}

double mesh_sample_metres(const tileformat::Tiling& tiling, int z, int steps) {
  const double crs = tiling.tile_size(z) / steps;
  return tiling.scheme == tileformat::Scheme::kGeodetic
             ? crs * 3.14159265358979323846 / 180 * 6378137.0
             : crs;
}

double MeshTileOptions::threshold(int z, int roots_x) const {
  const double level = error_scale * cesium_level_error(z, roots_x);
  return z == finest_zoom ? std::min(level, finest_error) : level;
}

std::vector<uint8_t> encode_mesh_tile(const tileformat::Tiling& tiling, TileId id,
                                      const TileGrid& grid, const MeshErrors& errors,
                                      const MeshTileOptions& options) {
  const int n = grid.steps;
  const std::vector<std::array<GridPoint, 3>> triangles =
      cut_mesh(errors, options.threshold(id.z, tiling.roots_x));
  // Vertices numbered by first use.
  std::vector<int32_t> number(size_t(n + 1) * (n + 1), -1);
  std::vector<GridPoint> vertices;
  QuantizedMeshTile t;
  t.triangles.reserve(triangles.size() * 3);
  for (const auto& tri : triangles)
    for (const GridPoint& p : tri) {
      int32_t& k = number[size_t(p.j) * (n + 1) + p.i];
      if (k < 0) {
        k = int32_t(vertices.size());
        vertices.push_back(p);
      }
      t.triangles.push_back(uint32_t(k));
    }

  // Heights: the header's float range holds every vertex.
  double lo = INFINITY, hi = -INFINITY;
  for (const GridPoint& p : vertices) {
    lo = std::min(lo, grid.at(p.i, p.j));
    hi = std::max(hi, grid.at(p.i, p.j));
  }
  float flo = float(lo), fhi = float(hi);
  if (double(flo) > lo) flo = std::nextafter(flo, -INFINITY);
  if (double(fhi) < hi) fhi = std::nextafter(fhi, INFINITY);
  t.min_height = flo, t.max_height = fhi;
  const double range = double(fhi) - double(flo);

  const SampleGeometry geo{tiling, id.z, n};
  const int64_t gx0 = int64_t(id.x) * n, gy0 = int64_t(id.y) * n;
  double north_lat, south_lat, lon;
  geo.lonlat(gx0, gy0, lon, north_lat);
  geo.lonlat(gx0, gy0 + n, lon, south_lat);
  const TileFrame frame(geo, gx0, gy0);
  std::vector<Vec3> positions;
  positions.reserve(vertices.size());
  for (const GridPoint& p : vertices) {
    const double h = grid.at(p.i, p.j);
    const int hq = range > 0 ? int(std::lround((h - flo) / range * kQuantizedMax)) : 0;
    const double plat = frame.lat_at(p.j);
    t.u.push_back(uint16_t((int64_t(p.i) * 2 * kQuantizedMax + n) / (2 * n)));
    if (tiling.scheme == tileformat::Scheme::kWebMercator)
      t.v.push_back(uint16_t(
          p.j == 0   ? kQuantizedMax
          : p.j == n ? 0
                     : std::lround((plat - south_lat) / (north_lat - south_lat) * kQuantizedMax)));
    else
      t.v.push_back(uint16_t((int64_t(n - p.j) * 2 * kQuantizedMax + n) / (2 * n)));
    t.height.push_back(uint16_t(hq));
    positions.push_back(frame.position(p.i, p.j, flo + range * hq / kQuantizedMax));
    if (options.normals) {
      const std::array<uint8_t, 2> oct = oct_encode(vertex_normal(grid, frame, p.i, p.j));
      t.oct_normals.push_back(oct[0]);
      t.oct_normals.push_back(oct[1]);
    }
  }

  // Edges, west and east south to north, south and north west to east.
  for (size_t k = 0; k < vertices.size(); ++k) {
    const GridPoint& p = vertices[k];
    if (p.i == 0) t.west.push_back(uint32_t(k));
    if (p.i == n) t.east.push_back(uint32_t(k));
    if (p.j == n) t.south.push_back(uint32_t(k));
    if (p.j == 0) t.north.push_back(uint32_t(k));
  }
  auto by_v = [&](uint32_t a, uint32_t b) { return t.v[a] < t.v[b]; };
  auto by_u = [&](uint32_t a, uint32_t b) { return t.u[a] < t.u[b]; };
  std::sort(t.west.begin(), t.west.end(), by_v);
  std::sort(t.east.begin(), t.east.end(), by_v);
  std::sort(t.south.begin(), t.south.end(), by_u);
  std::sort(t.north.begin(), t.north.end(), by_u);

  // Water mask: one byte for a tile all land or all water.
  if (options.water_mask) {
    double west, east, lat;
    geo.lonlat(gx0, gy0, west, lat);
    geo.lonlat(gx0 + n, gy0, east, lat);
    if (east <= west) east += 360;  // the tile ending on the antimeridian
    t.water_mask = options.water_mask(west, south_lat, east, north_lat);
    if (!t.water_mask.empty() && std::all_of(t.water_mask.begin(), t.water_mask.end(),
                                             [&](uint8_t b) { return b == t.water_mask[0]; }))
      t.water_mask.resize(1);
  }

  // Bounding sphere: the box's centre, the farthest vertex.
  Vec3 lo3{INFINITY, INFINITY, INFINITY}, hi3{-INFINITY, -INFINITY, -INFINITY};
  for (const Vec3& p : positions)
    for (int c = 0; c < 3; ++c)
      lo3[c] = std::min(lo3[c], p[c]), hi3[c] = std::max(hi3[c], p[c]);
  for (int c = 0; c < 3; ++c)
    t.sphere_center[c] = (lo3[c] + hi3[c]) / 2;
  for (const Vec3& p : positions)
    t.sphere_radius = std::max(t.sphere_radius, length(sub(p, t.sphere_center)));
  t.sphere_radius *= 1 + 1e-9;
  t.center = t.sphere_center;
  // Horizon occlusion point; a tile too large to have one (half the Earth)
  // gets a point 10^6 radii out above its centre: hidden only from cameras on
  // the far side of the Earth.
  const std::optional<Vec3> horizon = horizon_occlusion_point(positions, t.sphere_center);
  if (horizon) {
    t.horizon_point = *horizon;
  } else {  // along the normal at the tile's centre
    double clon, clat;
    geo.lonlat(gx0 + n / 2, gy0 + n / 2, clon, clat);
    const Vec3 up = ellipsoid_normal(clon, clat);
    for (int c = 0; c < 3; ++c)
      t.horizon_point[c] = up[c] * 1e6;
  }
  return encode_quantized_mesh(t);
}

std::vector<std::vector<TileId>> mesh_tile_plan(TerrainPackage& package) {
  std::vector<std::vector<TileId>> plan(size_t(package.max_zoom) + 1);
  for (int z = package.min_zoom; z <= package.max_zoom; ++z)
    plan[z] = package.reader->tile_ids(z);
  for (int z = package.min_zoom - 1; z >= 0; --z) {
    std::set<std::pair<uint32_t, uint32_t>> parents;
    for (const TileId& c : plan[z + 1])
      parents.insert({c.y / 2, c.x / 2});
    for (const auto& [y, x] : parents)
      plan[z].push_back({z, x, y});
  }
  for (uint32_t x = 0; x < uint32_t(package.tiling.roots_x); ++x)
    for (uint32_t y = 0; y < uint32_t(package.tiling.roots_y); ++y)
      if (std::none_of(plan[0].begin(), plan[0].end(),
                       [&](const TileId& id) { return id.x == x && id.y == y; }))
        plan[0].push_back({0, x, y});
  for (std::vector<TileId>& level : plan)
    std::sort(level.begin(), level.end(),
              [](const TileId& a, const TileId& b) { return a.y != b.y ? a.y < b.y : a.x < b.x; });
  return plan;
}

std::string layer_json(const TerrainPackage& package, const std::vector<std::vector<TileId>>& plan,
                       const std::string& name, const std::string& description, bool normals,
                       bool water_mask) {
  const tileformat::Tiling& t = package.tiling;
  const tileformat::Bounds& b = package.meta.common.lonlat;
  auto number = [](double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.10g", v);
    return std::string(buf);
  };
  std::string j = "{\n  \"tilejson\": \"2.1.0\",\n  \"name\": \"" + tileformat::json_escape(name) +
                  "\",\n  \"description\": \"" + tileformat::json_escape(description) +
                  "\",\n  \"version\": \"1.0.0\",\n  \"format\": \"quantized-mesh-1.0\",\n" +
                  "  \"scheme\": \"tms\",\n  \"tiles\": [\"{z}/{x}/{y}.terrain?v={version}\"],\n" +
                  "  \"projection\": \"" +
                  (t.scheme == tileformat::Scheme::kWebMercator ? "EPSG:3857" : "EPSG:4326") +
                  "\",\n  \"bounds\": [" + number(b.min_x) + ", " + number(b.min_y) + ", " +
                  number(b.max_x) + ", " + number(b.max_y) + "],\n  \"minzoom\": 0,\n" +
                  "  \"maxzoom\": " + std::to_string(plan.size() - 1) + ",\n  \"extensions\": [" +
                  (normals ? "\"octvertexnormals\"" : "") + (normals && water_mask ? ", " : "") +
                  (water_mask ? "\"watermask\"" : "") + "],\n  \"available\": [";
  // Per zoom, rectangles of TMS rows: runs of x in each row, merged over
  // consecutive rows with the same run.
  for (size_t z = 0; z < plan.size(); ++z) {
    const uint64_t rows = t.tiles_y(int(z));
    std::map<uint32_t, std::vector<std::pair<uint32_t, uint32_t>>> runs;  // TMS row -> runs
    for (const TileId& id : plan[z]) {
      auto& row = runs[uint32_t(rows - 1 - id.y)];
      if (!row.empty() && row.back().second + 1 == id.x)
        row.back().second = id.x;
      else
        row.push_back({id.x, id.x});
    }
    struct Rect {
      uint32_t x0, x1, y0, y1;
    };
    std::vector<Rect> done;
    std::map<std::pair<uint32_t, uint32_t>, Rect> open;
    for (auto& [row, list] : runs) {
      std::sort(list.begin(), list.end());
      std::map<std::pair<uint32_t, uint32_t>, Rect> next;
      for (const auto& run : list) {
        auto it = open.find(run);
        if (it != open.end() && it->second.y1 + 1 == row) {
          Rect r = it->second;
          r.y1 = row;
          next[run] = r;
          open.erase(it);
        } else {
          next[run] = {run.first, run.second, row, row};
        }
      }
      for (const auto& [_, r] : open)
        done.push_back(r);
      open = std::move(next);
    }
    for (const auto& [_, r] : open)
      done.push_back(r);
    std::sort(done.begin(), done.end(), [](const Rect& a, const Rect& c) {
      return a.y0 != c.y0 ? a.y0 < c.y0 : a.x0 < c.x0;
    });
    j += z ? ",\n    [" : "\n    [";
    for (size_t k = 0; k < done.size(); ++k)
      j += (k ? ", " : "") + std::string("{\"startX\": ") + std::to_string(done[k].x0) +
           ", \"startY\": " + std::to_string(done[k].y0) +
           ", \"endX\": " + std::to_string(done[k].x1) +
           ", \"endY\": " + std::to_string(done[k].y1) + "}";
    j += "]";
  }
  return j + "\n  ]\n}\n";
}

}  // namespace globe::web
