// Line-cluster tiles (lines, bundles) as Mapbox Vector Tiles (docs/web.md
// "Vector tiles"), one tile at a time, for the export and the server: one MVT
// layer per layer of the package's features table, each run a LINESTRING with
// the feature's id, its class ("class") and its attributes; lines of zero
// length as points tagged zero_length; a labelled feature's label as "name"
// (mvt_labels.hpp). Also the MapLibre style that draws the classes as the
// viewer does, and the names along the lines.
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

#include "runtime/line_package.hpp"
#include "tileformat/feature_table.hpp"
#include "tileformat/tile_id.hpp"
#include "web/feature_tags.hpp"
#include "web/mvt_encoder.hpp"
#include "web/mvt_labels.hpp"

namespace globe::web {

class LineMvtEncoder {
 public:
  // Reads the package's features table (an older package without one keeps
  // ids and classes only). Not thread-safe: one per thread, or a lock.
  explicit LineMvtEncoder(LinePackage& package);
  ~LineMvtEncoder();

  // The MVT bytes (not gzipped; empty if the tile holds nothing) of a
  // tile's blob. Throws InputError naming the package and tile for a blob
  // that does not decode.
  std::vector<uint8_t> encode(tileformat::TileId id, std::span<const uint8_t> blob);

  // What the tiles encoded so far held, for TileJSON and the style.
  uint64_t features() const { return features_count_; }
  uint64_t zero_length() const { return zero_length_; }
  const std::map<std::string, std::set<uint32_t>>& classes_in() const { return classes_in_; }
  const std::map<std::string, std::map<std::string, std::string>>& fields() const {
    return features_.fields();
  }
  const MvtLabels& labels() const { return labels_; }

 private:
  LinePackage& package_;
  MvtLabels labels_;
  FeatureTags features_;
  uint64_t features_count_ = 0, zero_length_ = 0;
  std::map<std::string, std::set<uint32_t>> classes_in_;  // MVT layer -> classes
};

// A MapLibre style (version 8) drawing the classes of `classes_in` as the
// viewer does (casings under fills, higher class ids on top) from the vector
// source at `source_url`; unless `glyphs` is empty, over them per MVT layer
// a symbol layer "LAYER:labels" writing each line's "name" along it.
std::string line_style_json(const LinePackage& package,
                            const std::map<std::string, std::set<uint32_t>>& classes_in,
                            const std::string& source_url, const StyleGlyphs& glyphs = {});

}  // namespace globe::web
