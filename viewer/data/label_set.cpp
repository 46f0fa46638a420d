// The view's labels (see label_set.hpp).
#include "data/label_set.hpp"
#include "runtime/package_open.hpp"

#include <algorithm>
#include <cstdio>
#include <numeric>

#include "runtime/errors.hpp"
#include "tileformat/error.hpp"
#include "tileformat/feature_table.hpp"
#include "tileformat/json.hpp"
#include "tileformat/package.hpp"

namespace globe::viewer {

namespace {

// The attribute `field` of a feature as label text ("" when absent).
std::string attribute_text(tileformat::FeatureTableReader& features, int64_t id,
                           const std::string& field) {
  const auto f = features.get(id);
  if (!f) return "";
  const tileformat::JsonValue props = tileformat::JsonValue::parse(f->properties);
  const tileformat::JsonValue* v = props.find(field);
  if (!v) return "";
  if (v->is_string()) return v->string();
  if (v->is_number()) {
    const double x = v->number();
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.10g", x);
    return buf;
  }
  return "";
}

}  // namespace

LabelSet::LabelSet(const std::vector<std::string>& packages, const std::string& field,
                   const std::string& font) {
  for (const std::string& path : packages) {
    if (is_url(path)) {  // the labels table is not served (docs/viewer.md "Remote sources")
      std::fprintf(stderr, "globe-view: note: %s: labels of remote sources are not read\n",
                   path.c_str());
      continue;
    }
    try {
      tileformat::PackageReader reader(path);
      if (!tileformat::has_labels(reader)) continue;
      const auto source = static_cast<uint32_t>(sources_.size());
      sources_.push_back(path);
      std::optional<tileformat::FeatureTableReader> features;
      if (!field.empty()) features.emplace(reader);
      const size_t first = labels_.size();
      tileformat::LabelTableReader(reader).for_each([&](const tileformat::LabelRecord& r) {
        LabelEntry e;
        e.source = source;
        e.record = r;
        if (features) e.record.text = attribute_text(*features, r.feature, field);
        if (!e.record.text.empty()) labels_.push_back(std::move(e));
      });
      // Ranks within the package: by priority, ties by id.
      const size_t n = labels_.size() - first;
      std::vector<size_t> order(n);
      std::iota(order.begin(), order.end(), first);
      std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
        return labels_[a].record.priority > labels_[b].record.priority;
      });
      for (size_t k = 0; k < n; ++k)
        labels_[order[k]].rank = 1.0 - double(k) / double(std::max<size_t>(n, 1));
    } catch (const tileformat::FormatError& e) {
      throw InputError(path + ": " + e.what());
    } catch (const tileformat::PackageError& e) {
      throw InputError(path + ": " + e.what());
    }
  }
  if (labels_.empty()) return;
  if (!font.empty()) {
    own_engine_ = std::make_unique<TextEngine>(font);
    engine_ = own_engine_.get();
  } else if (!(engine_ = default_text_engine())) {
    throw InputError("text: no fonts (install fonts-noto-core or fonts-dejavu-core)");
  }
}

LabelSet::~LabelSet() = default;

const ShapedLabel& LabelSet::shaped(LabelEntry& l) {
  if (!l.shaped) l.shaped = engine_->shape(l.record.text);
  return *l.shaped;
}

}  // namespace globe::viewer
