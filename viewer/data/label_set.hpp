// The labels of a view's vector packages (docs/viewer.md "Labels"): every
// row of their labels tables (tileformat/label_table.hpp), read once when
// the viewer opens, with the priority turned into a rank within its package
// (so population, areas and lengths mix), and each label's text shaped on
// first use (HarfBuzz through lib/text) with its glyphs in the SDF atlas.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "data/text_engine.hpp"
#include "tileformat/label_table.hpp"

namespace globe::viewer {

using LabelGlyph = ShapedGlyph;
using ShapedLabel = ShapedString;

struct LabelEntry {
  uint32_t source = 0;  // index into LabelSet::sources()
  tileformat::LabelRecord record;
  double rank = 0;  // 0..1, 1 the package's first
  std::optional<ShapedLabel> shaped;
};

class LabelSet {
 public:
  static constexpr float kAtlasPx = TextEngine::kAtlasPx;
  // `packages`: the vector packages of the view (those without a labels
  // table add nothing); `field`: an attribute to label with instead of the
  // stored text ("" for the stored text); `font`: a font file before
  // Debian's chain ("" for none). Throws InputError for a broken table or
  // an unreadable font.
  LabelSet(const std::vector<std::string>& packages, const std::string& field,
           const std::string& font);
  ~LabelSet();
  const std::vector<std::string>& sources() const { return sources_; }
  std::vector<LabelEntry>& labels() { return labels_; }
  const std::vector<LabelEntry>& labels() const { return labels_; }
  // The label's glyphs (shaped on first use).
  const ShapedLabel& shaped(LabelEntry& l);
  text::GlyphAtlas& atlas() { return engine_->atlas(); }
  // Labels whose glyphs did not fit the atlas.
  size_t atlas_misses() const { return engine_ ? engine_->atlas_misses() : 0; }

 private:
  std::vector<std::string> sources_;
  std::vector<LabelEntry> labels_;
  // Debian's chain is the legends' engine, shared (one atlas, the fonts read
  // once); a --label-font has an engine of its own.
  std::unique_ptr<TextEngine> own_engine_;
  TextEngine* engine_ = nullptr;
};

}  // namespace globe::viewer
