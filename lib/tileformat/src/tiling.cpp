// Tiling schemes (docs/tileformat.md §2).
#include "tileformat/tiling.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "tileformat/error.hpp"

namespace tileformat {
namespace {
std::string fmt(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}
}  // namespace

const char* scheme_name(Scheme scheme) {
  switch (scheme) {
    case Scheme::kWebMercator:
      return "webmercator";
    case Scheme::kGeodetic:
      return "geodetic";
    case Scheme::kLocal:
      return "local";
  }
  return "?";
}

std::optional<Scheme> parse_scheme(std::string_view name) {
  for (Scheme s : {Scheme::kWebMercator, Scheme::kGeodetic, Scheme::kLocal})
    if (name == scheme_name(s)) return s;
  return std::nullopt;
}

Tiling Tiling::webmercator() {
  return {Scheme::kWebMercator,
          "EPSG:3857",
          -kWebMercatorHalf,
          kWebMercatorHalf,
          2 * kWebMercatorHalf,
          1,
          1};
}

Tiling Tiling::geodetic() {
  return {Scheme::kGeodetic, "EPSG:4326", -180.0, 90.0, 180.0, 2, 1};
}

Tiling Tiling::local(std::string crs_wkt, double x, double y, double size) {
  return {Scheme::kLocal, std::move(crs_wkt), x, y, size, 1, 1};
}

Bounds Tiling::tile_bounds(TileId id) const {
  const double s = tile_size(id.z);
  const double x0 = origin_x + id.x * s, y1 = origin_y - id.y * s;
  return {x0, y1 - s, x0 + s, y1};
}

TileRange Tiling::tiles_covering(const Bounds& b, int z) const {
  const double s = tile_size(z);
  const double nx = static_cast<double>(tiles_x(z)), ny = static_cast<double>(tiles_y(z));
  const double fx0 = std::floor((b.min_x - origin_x) / s),
               fx1 = std::ceil((b.max_x - origin_x) / s) - 1;
  const double fy0 = std::floor((origin_y - b.max_y) / s),
               fy1 = std::ceil((origin_y - b.min_y) / s) - 1;
  TileRange r;
  if (!(fx1 >= 0 && fy1 >= 0 && fx0 < nx && fy0 < ny) || fx0 > fx1 || fy0 > fy1) return r;
  r.min_x = static_cast<uint32_t>(std::max(0.0, fx0));
  r.max_x = static_cast<uint32_t>(std::min(nx - 1, fx1));
  r.min_y = static_cast<uint32_t>(std::max(0.0, fy0));
  r.max_y = static_cast<uint32_t>(std::min(ny - 1, fy1));
  return r;
}

int Tiling::view_zoom(const Bounds& data, int min_zoom, int max_zoom) const {
  const double span = std::max(data.width(), data.height());
  int z = min_zoom;
  while (z < max_zoom && span <= tile_size(z + 1))
    ++z;
  return z;
}

void Tiling::to_metadata(std::map<std::string, std::string>& meta) const {
  meta["globe:scheme"] = scheme_name(scheme);
  meta["globe:crs"] = crs;
  meta["globe:origin"] = fmt(origin_x) + "," + fmt(origin_y);
  meta["globe:root_size"] = fmt(root_size);
  meta["globe:roots"] = std::to_string(roots_x) + "," + std::to_string(roots_y);
}

Tiling Tiling::from_metadata(const std::map<std::string, std::string>& meta) {
  auto get = [&](const char* key) {
    auto it = meta.find(key);
    if (it == meta.end())
      throw FormatError("3.2", std::string("metadata key ") + key + " is missing");
    return it->second;
  };
  Tiling t;
  const std::string scheme = get("globe:scheme");
  const auto parsed = parse_scheme(scheme);
  if (!parsed)
    throw FormatError(
        "3.2", "metadata globe:scheme '" + scheme + "' is not one of webmercator, geodetic, local");
  t.scheme = *parsed;
  t.crs = get("globe:crs");
  char comma = 0;
  std::istringstream origin(get("globe:origin")), roots(get("globe:roots"));
  if (!(origin >> t.origin_x >> comma >> t.origin_y) || comma != ',')
    throw FormatError("3.2", "metadata globe:origin is not 'x,y'");
  if (!(roots >> t.roots_x >> comma >> t.roots_y) || t.roots_x < 1 || t.roots_y < 1)
    throw FormatError("3.2", "metadata globe:roots is not 'nx,ny'");
  try {
    t.root_size = std::stod(get("globe:root_size"));
  } catch (const std::exception&) {
    throw FormatError("3.2", "metadata globe:root_size is not a number");
  }
  if (!(t.root_size > 0) || !std::isfinite(t.root_size))
    throw FormatError("3.2", "metadata globe:root_size must be positive");
  return t;
}

Bounds Tiling::lonlat_limits() const {
  const double lat = scheme == Scheme::kWebMercator ? kWebMercatorMaxLat : 90.0;
  return {-180.0, -lat, 180.0, lat};
}

}  // namespace tileformat
