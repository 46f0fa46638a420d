// Tiling schemes (docs/tileformat.md §2): where tile (z, x, y) lies in the
// scheme's CRS and where its block samples are. Pure arithmetic; the CRS is
// carried as WKT text for tools and viewers that need it.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <string_view>

#include "tileformat/tile_id.hpp"

namespace tileformat {

struct Bounds {
  double min_x = 0, min_y = 0, max_x = 0, max_y = 0;
  double width() const { return max_x - min_x; }
  double height() const { return max_y - min_y; }
  bool intersects(const Bounds& o) const {
    return min_x < o.max_x && o.min_x < max_x && min_y < o.max_y && o.min_y < max_y;
  }
};

struct TileRange {  // inclusive XYZ ranges; empty if min > max
  uint32_t min_x = 1, max_x = 0, min_y = 1, max_y = 0;
  bool empty() const { return min_x > max_x || min_y > max_y; }
  uint64_t count() const { return empty() ? 0 : uint64_t{max_x - min_x + 1} * (max_y - min_y + 1); }
};

// The tiling schemes (§2); their names are the `globe:scheme` values.
enum class Scheme { kWebMercator, kGeodetic, kLocal };

// "webmercator", "geodetic" or "local".
const char* scheme_name(Scheme scheme);
// The scheme of that name, or nullopt.
std::optional<Scheme> parse_scheme(std::string_view name);

struct Tiling {
  Scheme scheme = Scheme::kLocal;
  std::string crs;      // CRS as WKT2 (or an authority code such as EPSG:3857)
  double origin_x = 0;  // top-left corner of root (0, 0) in CRS units
  double origin_y = 0;
  double root_size = 0;  // edge length of one root tile in CRS units
  int roots_x = 1, roots_y = 1;

  static Tiling webmercator();
  static Tiling geodetic();
  // A single square root with top-left corner (x, y) and edge `size`.
  static Tiling local(std::string crs_wkt, double x, double y, double size);

  double tile_size(int z) const { return root_size / static_cast<double>(uint64_t{1} << z); }
  uint64_t tiles_x(int z) const { return uint64_t(roots_x) << z; }
  uint64_t tiles_y(int z) const { return uint64_t(roots_y) << z; }
  // Whether column 0 is the east neighbour of the last column (the global
  // schemes span 360 degrees of longitude).
  bool wraps_x() const { return scheme != Scheme::kLocal; }
  Bounds tile_bounds(TileId id) const;
  // Distance between neighbouring block samples at zoom z.
  double sample_spacing(int z, int steps) const { return tile_size(z) / steps; }
  // Tiles whose area intersects `b` (clipped to the scheme's extent).
  TileRange tiles_covering(const Bounds& b, int z) const;
  // The zoom of a package's default view (`center`): the deepest zoom whose
  // one tile still holds the data's wider side, within [min_zoom, max_zoom].
  // Every package kind uses this one rule.
  int view_zoom(const Bounds& data, int min_zoom, int max_zoom) const;
  Bounds extent() const {
    return {origin_x, origin_y - roots_y * root_size, origin_x + roots_x * root_size, origin_y};
  }
  // The longitude/latitude range a package's `bounds` may take: webmercator
  // ends at +-85.0511 degrees (readers such as GDAL reject bounds past it).
  Bounds lonlat_limits() const;
  // Tiles across 360 degrees of longitude at zoom 0, where the tiling wraps
  // around the Earth (geodetic: 2, webmercator: 1); 0 for a local tiling.
  int wrap_tiles() const { return scheme == Scheme::kLocal ? 0 : static_cast<int>(roots_x); }
  bool contains(TileId id) const {
    return id.z >= 0 && id.z <= kMaxZoom && id.x < tiles_x(id.z) && id.y < tiles_y(id.z);
  }

  // Metadata keys (globe:scheme, globe:crs, globe:origin, globe:root_size,
  // globe:roots) and back; throws FormatError(§3.2) if incomplete.
  void to_metadata(std::map<std::string, std::string>& meta) const;
  static Tiling from_metadata(const std::map<std::string, std::string>& meta);
};

inline constexpr double kWebMercatorHalf = 20037508.342789244;
inline constexpr double kWebMercatorMaxLat = 85.051128779806589;  // atan(sinh(pi)), degrees

}  // namespace tileformat
