// FreetypeFaces: lib/text's one wrapper of FreeType — a FreeType library and
// one face per font file, every return code checked and thrown as TextError
// naming the file. FontSet reads names and coverage through it; SdfRenderer
// reads glyph outlines through it. Not thread-safe (FreeType faces are not): each owner
// holds its own.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace globe::text::detail {

struct FtPoint {
  float x = 0, y = 0;  // pixels, y up, the pen at the origin
};

// A glyph's outline as FreeType loads it unhinted, its curves flattened.
struct FtOutline {
  float advance_px = 0;   // unhinted horizontal advance
  bool even_odd = false;  // FreeType's fill rule for it (nonzero otherwise)
  // FreeType's control box, pixels; empty contours: a blank glyph (space).
  float x_min = 0, y_min = 0, x_max = 0, y_max = 0;
  // Closed polylines (the last point joins the first), curves flattened to
  // within the tolerance asked for.
  std::vector<std::vector<FtPoint>> contours;
};

class FreetypeFaces {
 public:
  // Opens every file (TextError naming the one that fails). A face without a
  // Unicode character map is an error too: nothing could be found in it.
  explicit FreetypeFaces(const std::vector<std::string>& paths);
  ~FreetypeFaces();
  FreetypeFaces(const FreetypeFaces&) = delete;
  FreetypeFaces& operator=(const FreetypeFaces&) = delete;

  size_t size() const;
  std::string family(size_t font) const;
  std::string style(size_t font) const;
  // Every code point the font maps to a glyph, ascending.
  std::vector<char32_t> code_points(size_t font) const;
  uint32_t glyph_index(size_t font, char32_t c) const;  // 0: none
  uint32_t glyph_count(size_t font) const;

  // Sets every face to size_px per em (72 dpi, as node-fontnik sets it).
  void set_size(int size_px);
  // size->metrics.ascender / 64 at the current size (truncated, as node-fontnik).
  int ascender_px(size_t font) const;
  // Loads the glyph unhinted (as node-fontnik) at the current size and
  // flattens its outline. TextError for a glyph id the font lacks. A glyph
  // without an outline (bitmap-only fonts) comes back blank.
  FtOutline outline(size_t font, uint32_t glyph, float tolerance_px);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace globe::text::detail
