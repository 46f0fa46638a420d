// Area tiles as Mapbox Vector Tiles (docs/web.md "Vector tiles", docs/areas.md),
// one tile at a time, for the export and the server: one MVT layer per layer
// of the package's features table, each feature's polygons in the tile one
// POLYGON or MULTIPOLYGON with the feature's id, its class ("class": the
// style class, or the choropleth class 1..k, 0 for no data), its attributes
// and, in a choropleth, its value ("value": the field, or field / denominator);
// with labels (mvt_labels.hpp), a labelled feature's label as "name", and a
// point layer "labels": one POINT per labelled feature at its label's anchor
// in the one tile of each zoom that holds the anchor (where the feature is
// drawn at that zoom), with "name" and "rank" (1 for the highest priority).
// Also the MapLibre style: fills (a choropleth as a `step` expression with
// the package's breaks and colours) under outlines, the names over them.
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
#include "web/mvt_labels.hpp"

namespace globe::web {

// The fills' opacity on web maps (over a basemap or hillshade): the style's
// and the drawn tiles' (runtime's area_looks).
inline constexpr double kAreaWebFillOpacity = 0.8;

// The MVT layer of the label points: "labels", or "labels_points" where a
// layer of the package's features has that name.
std::string area_label_layer(const AreaPackage& package);

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
  const MvtLabels& labels() const { return labels_; }

 private:
  AreaPackage& package_;
  MvtLabels labels_;
  std::string label_layer_;
  FeatureTags features_;
  uint64_t features_count_ = 0;
  std::map<std::string, std::set<uint32_t>> classes_in_;
};

// A MapLibre style (version 8) for the tiles at `source_url`: per MVT layer
// the fills (per class, or the choropleth's step and its no-data fill),
// then the outlines; unless `glyphs` is empty, over them a symbol layer
// "labels" writing the label points' names, the higher priority first.
std::string area_style_json(const AreaPackage& package,
                            const std::map<std::string, std::set<uint32_t>>& classes_in,
                            const std::string& source_url, const StyleGlyphs& glyphs = {});

}  // namespace globe::web
