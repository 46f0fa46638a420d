// Area tiles as Mapbox Vector Tiles (docs/web.md "Vector tiles", docs/areas.md),
// one tile at a time, for the export and the server: one MVT layer per layer
// of the package's features table, each feature's polygons in the tile one
// POLYGON or MULTIPOLYGON with the feature's id, its class ("class": the
// style class, or the choropleth class 1..k, 0 for no data), its attributes
// and, in a choropleth, its value ("value": the field, or field / denominator).
// Also the MapLibre style: fills (a choropleth as a `step` expression with
// the package's breaks and colours) under outlines.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <set>
#include <span>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "runtime/area_package.hpp"
#include "tileformat/feature_table.hpp"
#include "tileformat/tile_id.hpp"
#include "web/feature_tags.hpp"
#include "web/mvt_encoder.hpp"

namespace globe::web {

// The fills' opacity on web maps (over a basemap or hillshade): the style's
// and the drawn tiles' (runtime's area_looks).
inline constexpr double kAreaWebFillOpacity = 0.8;

class AreaMvtEncoder {
 public:
  // Not thread-safe: one per thread, or a lock.
  explicit AreaMvtEncoder(AreaPackage& package);
  ~AreaMvtEncoder();

  // The MVT bytes (not gzipped; empty if the tile holds nothing) of a
  // tile's blob. Throws InputError naming the package and tile for a blob
  // that does not decode.
  std::vector<uint8_t> encode(tileformat::TileId id, std::span<const uint8_t> blob);

  uint64_t features() const { return features_count_; }
  const std::map<std::string, std::set<uint32_t>>& classes_in() const { return classes_in_; }
  const std::map<std::string, std::map<std::string, std::string>>& fields() const {
    return features_.fields();
  }

 private:
  AreaPackage& package_;
  FeatureTags features_;
  uint64_t features_count_ = 0;
  std::map<std::string, std::set<uint32_t>> classes_in_;
};

// A MapLibre style (version 8) for the tiles at `source_url`: per MVT layer
// the fills (per class, or the choropleth's step and its no-data fill),
// then the outlines.
std::string area_style_json(const AreaPackage& package,
                            const std::map<std::string, std::set<uint32_t>>& classes_in,
                            const std::string& source_url);

}  // namespace globe::web
