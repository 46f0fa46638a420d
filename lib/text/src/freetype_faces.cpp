// FreeType, called from here only: opening faces, their names and character
// maps, sizes, and glyph outlines (FT_Outline_Decompose, curves flattened
// here into line segments). Every FT_Error is turned into a TextError naming
// the file and the glyph.
#include "freetype_faces.hpp"

#include <ft2build.h>
#include FT_FREETYPE_H
#include FT_OUTLINE_H

#include <algorithm>
#include <cmath>
#include <utility>

#include "text/font_set.hpp"

namespace globe::text::detail {
namespace {

std::string ft_message(FT_Error error) {
  const char* text = FT_Error_String(error);  // null when built without error strings
  return text != nullptr ? std::string(text) : "FreeType error " + std::to_string(error);
}

}  // namespace

struct FreetypeFaces::Impl {
  FT_Library library = nullptr;
  std::vector<FT_Face> faces;
  std::vector<std::string> paths;

  ~Impl() {
    for (FT_Face face : faces)
      FT_Done_Face(face);
    if (library != nullptr) FT_Done_FreeType(library);
  }
  void check(FT_Error error, size_t font, const std::string& what) const {
    if (error != 0) {
      throw TextError(paths[font] + ": " + what + ": " + ft_message(error));
    }
  }
};

FreetypeFaces::FreetypeFaces(const std::vector<std::string>& paths)
    : impl_(std::make_unique<Impl>()) {
  if (FT_Error error = FT_Init_FreeType(&impl_->library); error != 0) {
    impl_->library = nullptr;
    throw TextError("FreeType: cannot start: " + ft_message(error) + "; reinstall libfreetype6");
  }
  impl_->paths = paths;
  impl_->faces.reserve(paths.size());
  for (const std::string& path : paths) {
    FT_Face face = nullptr;
    if (FT_Error error = FT_New_Face(impl_->library, path.c_str(), 0, &face); error != 0) {
      throw TextError(path + ": cannot open as a font (" + ft_message(error) +
                      "); pass a TrueType or OpenType file");
    }
    impl_->faces.push_back(face);
    if (FT_Select_Charmap(face, FT_ENCODING_UNICODE) != 0) {
      throw TextError(path + ": the font has no Unicode character map; pass another font");
    }
  }
}

FreetypeFaces::~FreetypeFaces() = default;

size_t FreetypeFaces::size() const {
  return impl_->faces.size();
}

std::string FreetypeFaces::family(size_t font) const {
  const char* name = impl_->faces.at(font)->family_name;
  return name != nullptr ? name : "";
}

std::string FreetypeFaces::style(size_t font) const {
  const char* name = impl_->faces.at(font)->style_name;
  return name != nullptr ? name : "";
}

std::vector<char32_t> FreetypeFaces::code_points(size_t font) const {
  FT_Face face = impl_->faces.at(font);
  std::vector<char32_t> out;
  FT_UInt index = 0;
  for (FT_ULong c = FT_Get_First_Char(face, &index); index != 0;
       c = FT_Get_Next_Char(face, c, &index)) {
    out.push_back(static_cast<char32_t>(c));
  }
  return out;  // FreeType walks the map in ascending order
}

uint32_t FreetypeFaces::glyph_index(size_t font, char32_t c) const {
  return FT_Get_Char_Index(impl_->faces.at(font), c);
}

uint32_t FreetypeFaces::glyph_count(size_t font) const {
  return static_cast<uint32_t>(impl_->faces.at(font)->num_glyphs);
}

void FreetypeFaces::set_size(int size_px) {
  for (size_t i = 0; i < impl_->faces.size(); ++i) {
    impl_->check(FT_Set_Char_Size(impl_->faces[i], 0, static_cast<FT_F26Dot6>(size_px) * 64, 0, 0),
                 i, "cannot set the size to " + std::to_string(size_px) + " px");
  }
}

int FreetypeFaces::ascender_px(size_t font) const {
  return static_cast<int>(impl_->faces.at(font)->size->metrics.ascender / 64);
}

FtOutline FreetypeFaces::outline(size_t font, uint32_t glyph, float tolerance_px) {
  FT_Face face = impl_->faces.at(font);
  const std::string which = "glyph " + std::to_string(glyph);
  if (glyph >= static_cast<uint32_t>(face->num_glyphs)) {
    throw TextError(impl_->paths[font] + ": " + which + " is out of range (the font has " +
                    std::to_string(face->num_glyphs) + ")");
  }
  impl_->check(FT_Load_Glyph(face, glyph, FT_LOAD_NO_HINTING), font, "cannot load " + which);
  FT_GlyphSlot slot = face->glyph;
  FtOutline out;
  out.advance_px = static_cast<float>(slot->metrics.horiAdvance) / 64.0f;
  if (slot->format != FT_GLYPH_FORMAT_OUTLINE || slot->outline.n_contours <= 0) return out;
  out.even_odd = (slot->outline.flags & FT_OUTLINE_EVEN_ODD_FILL) != 0;
  FT_BBox box{};
  FT_Outline_Get_CBox(&slot->outline, &box);
  out.x_min = static_cast<float>(box.xMin) / 64.0f;
  out.y_min = static_cast<float>(box.yMin) / 64.0f;
  out.x_max = static_cast<float>(box.xMax) / 64.0f;
  out.y_max = static_cast<float>(box.yMax) / 64.0f;

  struct Flattener {
    FtOutline* out;
    float tolerance;
    FtPoint last;
    static FtPoint point(const FT_Vector* v) {
      return {static_cast<float>(v->x) / 64.0f, static_cast<float>(v->y) / 64.0f};
    }
    void line(FtPoint p) {
      out->contours.back().push_back(p);
      last = p;
    }
    // A Bezier curve's chord error with n pieces is at most its second
    // difference's size / (8 n^2) (quadratic) or 3/4 of the largest / n^2
    // (cubic): n is the smallest that keeps it under the tolerance.
    int pieces(float second_difference, float factor) const {
      const float n = std::ceil(std::sqrt(second_difference * factor / tolerance));
      return std::clamp(static_cast<int>(n), 1, 64);
    }
    static float length(float x, float y) { return std::sqrt(x * x + y * y); }
  };
  FT_Outline_Funcs funcs{};
  funcs.move_to = [](const FT_Vector* to, void* user) {
    auto* f = static_cast<Flattener*>(user);
    f->out->contours.emplace_back();
    f->line(Flattener::point(to));
    return 0;
  };
  funcs.line_to = [](const FT_Vector* to, void* user) {
    static_cast<Flattener*>(user)->line(Flattener::point(to));
    return 0;
  };
  funcs.conic_to = [](const FT_Vector* control, const FT_Vector* to, void* user) {
    auto* f = static_cast<Flattener*>(user);
    const FtPoint p0 = f->last, c = Flattener::point(control), p1 = Flattener::point(to);
    const int n =
        f->pieces(Flattener::length(p0.x - 2 * c.x + p1.x, p0.y - 2 * c.y + p1.y), 0.125f);
    for (int i = 1; i <= n; ++i) {
      const float t = static_cast<float>(i) / static_cast<float>(n), u = 1 - t;
      f->line({u * u * p0.x + 2 * u * t * c.x + t * t * p1.x,
               u * u * p0.y + 2 * u * t * c.y + t * t * p1.y});
    }
    return 0;
  };
  funcs.cubic_to = [](const FT_Vector* control1, const FT_Vector* control2, const FT_Vector* to,
                      void* user) {
    auto* f = static_cast<Flattener*>(user);
    const FtPoint p0 = f->last, c1 = Flattener::point(control1), c2 = Flattener::point(control2),
                  p1 = Flattener::point(to);
    const float dd = std::max(Flattener::length(p0.x - 2 * c1.x + c2.x, p0.y - 2 * c1.y + c2.y),
                              Flattener::length(c1.x - 2 * c2.x + p1.x, c1.y - 2 * c2.y + p1.y));
    const int n = f->pieces(dd, 0.75f);
    for (int i = 1; i <= n; ++i) {
      const float t = static_cast<float>(i) / static_cast<float>(n), u = 1 - t;
      const float a = u * u * u, b = 3 * u * u * t, d = 3 * u * t * t, e = t * t * t;
      f->line(
          {a * p0.x + b * c1.x + d * c2.x + e * p1.x, a * p0.y + b * c1.y + d * c2.y + e * p1.y});
    }
    return 0;
  };
  Flattener flattener{&out, tolerance_px, {}};
  impl_->check(FT_Outline_Decompose(&slot->outline, &funcs, &flattener), font,
               "cannot read the outline of " + which);
  return out;
}

}  // namespace globe::text::detail
