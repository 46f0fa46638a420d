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

#include "text/font_set.hpp"
#include "text/glyph_atlas.hpp"
#include "text/sdf_glyph.hpp"
#include "text/shaping.hpp"
#include "tileformat/label_table.hpp"

namespace globe::viewer {

// One glyph of a shaped label, at the atlas's size (kAtlasPx per em).
struct LabelGlyph {
  float x = 0;  // pen position from the text's start, px at kAtlasPx
  float y = 0;  // from the baseline, up
  float advance = 0;
  const text::GlyphAtlas::Entry* atlas = nullptr;  // nullptr: blank (a space)
};

struct ShapedLabel {
  std::vector<LabelGlyph> glyphs;
  float width = 0, ascent = 0, descent = 0;  // px at kAtlasPx
  bool ok = false;                           // shaped and every glyph in the atlas
};

struct LabelEntry {
  uint32_t source = 0;  // index into LabelSet::sources()
  tileformat::LabelRecord record;
  double rank = 0;  // 0..1, 1 the package's first
  std::optional<ShapedLabel> shaped;
};

class LabelSet {
 public:
  static constexpr float kAtlasPx = 24;  // the SDF glyphs' size per em
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
  text::GlyphAtlas& atlas() { return *atlas_; }
  // Labels whose glyphs did not fit the atlas.
  size_t atlas_misses() const { return atlas_misses_; }

 private:
  std::vector<std::string> sources_;
  std::vector<LabelEntry> labels_;
  std::unique_ptr<text::FontSet> fonts_;
  std::unique_ptr<text::Shaper> shaper_;
  std::unique_ptr<text::SdfRenderer> sdf_;
  std::unique_ptr<text::GlyphAtlas> atlas_;
  size_t atlas_misses_ = 0;
};

}  // namespace globe::viewer
