// FontSet: the fallback chain of font files labels are drawn with — the first
// font that has a character draws it. Its neighbours: shaping.hpp (lays a line
// out over the chain), sdf_glyph.hpp (renders the chain's glyphs),
// glyph_pbf.hpp (writes them for MapLibre). No FreeType types in this header.
//
// Thread safety: a FontSet is immutable once built; every const member may be
// called from several threads at once. Shaper and SdfRenderer keep a
// reference to it: it must outlive them.
#pragma once

#include <cstddef>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace globe::text {

// Every error of lib/text: a font that cannot be read, a missing package, a
// PBF that cannot be written. The message names the file and what to do.
struct TextError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// A fallback chain of font files: the first font that has a character draws it.
class FontSet {
 public:
  // Debian's fonts, in this order: `first` (a user's --label-font file, when
  // not empty; an unreadable file is an error), NotoSans-Regular (Latin, Greek,
  // Cyrillic), NotoSansArabic-Regular, NotoSansHebrew-Regular,
  // NotoSansDevanagari-Regular, NotoSansBengali-Regular, NotoSansThai-Regular,
  // NotoSansGeorgian-Regular, NotoSansArmenian-Regular, NotoSansEthiopic-Regular,
  // then DejaVuSans.ttf; missing files are skipped; none at all -> TextError
  // naming the packages to install (fonts-noto-core, fonts-dejavu-core).
  // `bold`: the -Bold files where they exist (DejaVuSans-Bold.ttf).
  static FontSet debian(const std::string& first = "", bool bold = false);

  // The chain in this order (at least one file). TextError on a file FreeType
  // cannot open, or a font with no Unicode character map.
  explicit FontSet(std::vector<std::string> paths);
  ~FontSet();
  // A moved-from FontSet may only be destroyed or assigned to.
  FontSet(FontSet&&) noexcept;
  FontSet& operator=(FontSet&&) noexcept;

  size_t size() const;
  const std::string& path(size_t font) const;
  std::string family(size_t font) const;  // FreeType's family name, e.g. "Noto Sans"
  std::string style(size_t font) const;   // FreeType's style name, e.g. "Regular"
  // The first font with a glyph for c; -1 for none.
  int font_for(char32_t c) const;
  // Whether font `font` has a glyph for c.
  bool has(size_t font, char32_t c) const;
  // A name for the chain as MapLibre fontstacks are named: the first font's
  // family and style, as node-fontnik names a font ("Noto Sans Regular").
  std::string fontstack_name() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace globe::text
