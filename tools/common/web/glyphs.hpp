// The glyphs of the generated MapLibre styles' labels (docs/web.md "Labels"):
// MapLibre glyph PBFs, "{fontstack}/{start}-{end}.pbf", SDF at 24 px with a
// border of 3, of Debian's font chain (lib/text: FontSet::debian(),
// glyph_pbf.hpp), so a web map draws the labels without an outside glyph
// server. `globe-vectorize export` writes them beside its style; globe-serve
// answers /fonts/{fontstack}/{range}.pbf from the same code. The one user
// of lib/text in tools/.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

namespace globe::web {

class GlyphSet {
 public:
  // Debian's fonts (fonts-noto-core, fonts-dejavu-core). Throws InputError
  // ("glyphs: ...") naming the packages to install when none can be read.
  GlyphSet();
  ~GlyphSet();
  GlyphSet(const GlyphSet&) = delete;
  GlyphSet& operator=(const GlyphSet&) = delete;

  // The fontstack the PBFs are named by and the styles' text-font names
  // ("Noto Sans Regular": the first font's family and style, as fontnik
  // names them).
  const std::string& fontstack() const;

  // Whether some font has a glyph in start..start+255 (start a multiple of
  // 256 in the Basic Multilingual Plane, the code points MapLibre GL asks
  // for); false for any other start.
  bool has_range(uint32_t start) const;
  // The PBF of that range, nullptr when !has_range(start). Made on first
  // ask (a few milliseconds; every range 0.7 s) and kept: at most 256 of
  // them, about 3 MB. Safe from several threads (they wait for one another
  // while a range is made).
  std::shared_ptr<const std::string> range(uint32_t start) const;

  // Writes every range that has a glyph as DIR/{fontstack}/{start}-{end}.pbf
  // (folders made as needed; existing files replaced); returns how many.
  // Throws OutputError naming the file that cannot be written.
  size_t write(const std::string& dir) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace globe::web
