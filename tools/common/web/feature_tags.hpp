// A vector package's features as MVT tags (docs/web.md "Vector tiles"), for
// the line and area encoders: each feature's MVT layer (its layer in the
// features table) and its attributes as tags, read once and cached; and the
// fields each MVT layer carries, for TileJSON's vector_layers. With the
// package's labels (mvt_labels.hpp), a labelled feature's "name" is its label.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "tileformat/feature_table.hpp"
#include "tileformat/json.hpp"
#include "tileformat/package.hpp"
#include "web/mvt_encoder.hpp"

namespace globe::web {

using MvtTags = std::vector<std::pair<std::string, MvtValue>>;
class MvtLabels;

class FeatureTags {
 public:
  struct Feature {
    std::string layer;
    MvtTags tags;
  };
  // `reserved`: attribute names the encoder sets itself (left out);
  // `fallback_layer`: the layer of features without one (or without a
  // features table: an older package keeps ids and classes only); `extra`
  // adds tags from a feature's parsed attributes (e.g. a choropleth value);
  // `labels` (kept by reference; may be null): a labelled feature's "name"
  // tag is its label's text, in place of an attribute of that name.
  FeatureTags(tileformat::PackageReader& reader, std::string fallback_layer,
              std::set<std::string> reserved,
              std::function<void(const tileformat::JsonValue&, MvtTags&)> extra = {},
              const MvtLabels* labels = nullptr);
  ~FeatureTags();

  const Feature& get(uint64_t id);
  // Records the types of `tags` under `layer` (String, Number or Boolean).
  void note_fields(const std::string& layer, const MvtTags& tags);
  const std::map<std::string, std::map<std::string, std::string>>& fields() const {
    return fields_;
  }
  std::map<std::string, std::string>& fields_of(const std::string& layer) { return fields_[layer]; }

 private:
  std::unique_ptr<tileformat::FeatureTableReader> table_;
  std::string fallback_;
  std::set<std::string> reserved_;
  std::function<void(const tileformat::JsonValue&, MvtTags&)> extra_;
  const MvtLabels* labels_ = nullptr;
  std::unordered_map<uint64_t, Feature> cache_;                       // cleared when large
  std::map<std::string, std::map<std::string, std::string>> fields_;  // layer -> key -> type
};

}  // namespace globe::web
