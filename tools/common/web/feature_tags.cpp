// Features as MVT tags (see feature_tags.hpp).
#include "web/feature_tags.hpp"

#include "tileformat/error.hpp"
#include "web/mvt_labels.hpp"

namespace globe::web {

FeatureTags::FeatureTags(tileformat::PackageReader& reader, std::string fallback_layer,
                         std::set<std::string> reserved,
                         std::function<void(const tileformat::JsonValue&, MvtTags&)> extra,
                         const MvtLabels* labels)
    : fallback_(std::move(fallback_layer)),
      reserved_(std::move(reserved)),
      extra_(std::move(extra)),
      labels_(labels) {
  try {
    table_ = std::make_unique<tileformat::FeatureTableReader>(reader);
  } catch (const tileformat::FormatError&) {
    table_.reset();  // an older package: ids and classes only
  }
}

FeatureTags::~FeatureTags() = default;

const FeatureTags::Feature& FeatureTags::get(uint64_t id) {
  if (auto it = cache_.find(id); it != cache_.end()) return it->second;
  if (cache_.size() > 200000) cache_.clear();
  Feature f{fallback_, {}};
  if (table_)
    if (const auto rec = table_->get(int64_t(id))) {
      f.layer = rec->layer.empty() ? fallback_ : rec->layer;
      try {
        const tileformat::JsonValue props = tileformat::JsonValue::parse(rec->properties);
        if (props.is_object())
          for (const auto& [k, v] : props.members())
            if (!reserved_.count(k)) f.tags.emplace_back(k, MvtValue::from_json(v));
        if (extra_) extra_(props, f.tags);
      } catch (const tileformat::JsonError&) {
        // attributes that are not JSON: the feature keeps its id and class
      }
    }
  if (labels_)
    if (const std::string* name = labels_->text(id)) set_name_tag(f.tags, *name);
  return cache_.emplace(id, std::move(f)).first->second;
}

void FeatureTags::note_fields(const std::string& layer, const MvtTags& tags) {
  auto& known = fields_[layer];
  for (const auto& [k, v] : tags)
    known.try_emplace(k, v.kind == MvtValue::Kind::kString ? "String"
                         : v.kind == MvtValue::Kind::kBool ? "Boolean"
                                                           : "Number");
}

}  // namespace globe::web
