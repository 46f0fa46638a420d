// SdfRenderer: the exact signed distance to a glyph's outline, from the
// outline FreeType loads (freetype_faces.cpp, curves flattened to 1/64 px).
// Each texel's centre gets the distance to the nearest segment — every
// segment visits only the texels within reach of it, the distance at which
// the field is clamped (0.75 * radius outside, 0.25 * radius inside) — and
// its side from the outline's fill rule, counted along the texel's row.
// Then v = 255 - 255 * (d / radius + 0.25). The bitmap covers FreeType's
// control box on the pixel grid plus the border: the box FreeType's own
// FT_RENDER_MODE_SDF renders (tests/text_test.cpp compares the two texel by
// texel: within 4 of 255). Not FreeType's renderer itself: it costs 2.5 ms a
// glyph at 24 px (27 s for the Basic Multilingual Plane of Debian's chain,
// this about 0.5 s), and FreeType 2.12 takes the sign from the nearest edge,
// which goes wrong at some sharp corners (a texel of Noto Sans 'M', most of
// U+2E4E); the winding number does not.
#include "text/sdf_glyph.hpp"

#include <algorithm>
#include <cmath>
#include <mutex>

#include "freetype_faces.hpp"

namespace globe::text {

namespace {

constexpr float kFlatteningPx = 1.0f / 64;

struct Segment {
  detail::FtPoint a, b;
};

std::vector<Segment> segments_of(const detail::FtOutline& outline) {
  std::vector<Segment> out;
  for (const std::vector<detail::FtPoint>& contour : outline.contours) {
    for (size_t i = 0; i < contour.size(); ++i) {
      const detail::FtPoint& a = contour[i];
      const detail::FtPoint& b = contour[(i + 1) % contour.size()];
      if (a.x != b.x || a.y != b.y) out.push_back({a, b});
    }
  }
  return out;
}

float squared_distance(float px, float py, const Segment& s) {
  const float dx = s.b.x - s.a.x, dy = s.b.y - s.a.y;
  const float length2 = dx * dx + dy * dy;
  float t = length2 > 0 ? ((px - s.a.x) * dx + (py - s.a.y) * dy) / length2 : 0;
  t = std::clamp(t, 0.0f, 1.0f);
  const float ex = s.a.x + t * dx - px, ey = s.a.y + t * dy - py;
  return ex * ex + ey * ey;
}

}  // namespace

struct SdfRenderer::Impl {
  const FontSet& fonts;
  int size_px, border;
  float radius;
  detail::FreetypeFaces faces;
  std::mutex mutex;  // FreeType faces are used by one thread at a time

  Impl(const FontSet& f, int size, int b, float r)
      : fonts(f), size_px(size), border(b), radius(r), faces(paths(f)) {
    faces.set_size(size_px);
  }
  static std::vector<std::string> paths(const FontSet& fonts) {
    std::vector<std::string> out;
    for (size_t i = 0; i < fonts.size(); ++i)
      out.push_back(fonts.path(i));
    return out;
  }

  SdfGlyph render(uint16_t font, uint32_t glyph_id) {  // with the mutex held
    if (font >= faces.size()) {
      throw TextError("SdfRenderer: font " + std::to_string(font) + " is not in the chain of " +
                      std::to_string(faces.size()));
    }
    const detail::FtOutline outline = faces.outline(font, glyph_id, kFlatteningPx);
    SdfGlyph out;
    out.advance = outline.advance_px;
    const std::vector<Segment> segments = segments_of(outline);
    if (segments.empty()) return out;
    // FreeType's bitmap box: the control box rounded out, at least a pixel.
    const int x0 = static_cast<int>(std::floor(outline.x_min));
    const int y1 = static_cast<int>(std::ceil(outline.y_max));
    const int w = std::max(1, static_cast<int>(std::ceil(outline.x_max)) - x0);
    const int h = std::max(1, y1 - static_cast<int>(std::floor(outline.y_min)));
    out.left = x0 - border;
    out.top = y1 + border;
    out.width = w + 2 * border;
    out.height = h + 2 * border;
    const size_t texels = static_cast<size_t>(out.width) * static_cast<size_t>(out.height);

    // Texel (i, j) has its centre at x = left + i + 0.5, y = top - j - 0.5.
    const float reach = 0.75f * radius;  // beyond it the field is clamped either side
    std::vector<float> nearest(texels, reach * reach);
    for (const Segment& s : segments) {
      const float sx0 = std::min(s.a.x, s.b.x) - reach, sx1 = std::max(s.a.x, s.b.x) + reach;
      const float sy0 = std::min(s.a.y, s.b.y) - reach, sy1 = std::max(s.a.y, s.b.y) + reach;
      const int i0 = std::max(0, static_cast<int>(std::floor(sx0 - out.left - 0.5f)));
      const int i1 = std::min(out.width - 1, static_cast<int>(std::ceil(sx1 - out.left - 0.5f)));
      const int j0 = std::max(0, static_cast<int>(std::floor(out.top - sy1 - 0.5f)));
      const int j1 = std::min(out.height - 1, static_cast<int>(std::ceil(out.top - sy0 - 0.5f)));
      for (int j = j0; j <= j1; ++j) {
        const float py = static_cast<float>(out.top - j) - 0.5f;
        float* row = nearest.data() + static_cast<size_t>(j) * out.width;
        for (int i = i0; i <= i1; ++i) {
          const float px = static_cast<float>(out.left + i) + 0.5f;
          row[i] = std::min(row[i], squared_distance(px, py, s));
        }
      }
    }

    // Inside or out: the winding number of the segments crossing the
    // texel row's centre line to the left of the texel.
    out.pixels.resize(texels);
    std::vector<std::pair<float, int>> crossings;
    for (int j = 0; j < out.height; ++j) {
      const float py = static_cast<float>(out.top - j) - 0.5f;
      crossings.clear();
      for (const Segment& s : segments) {
        const bool up = s.a.y <= py && s.b.y > py, down = s.b.y <= py && s.a.y > py;
        if (!up && !down) continue;
        const float x = s.a.x + (py - s.a.y) * (s.b.x - s.a.x) / (s.b.y - s.a.y);
        crossings.emplace_back(x, up ? 1 : -1);
      }
      std::sort(crossings.begin(), crossings.end());
      size_t next = 0;
      int winding = 0;
      for (int i = 0; i < out.width; ++i) {
        const float px = static_cast<float>(out.left + i) + 0.5f;
        while (next < crossings.size() && crossings[next].first < px) {
          winding += crossings[next++].second;
        }
        const bool inside = outline.even_odd ? (winding % 2) != 0 : winding != 0;
        const size_t k = static_cast<size_t>(j) * out.width + i;
        const float d = std::sqrt(nearest[k]) * (inside ? -1.0f : 1.0f);
        const float v = 255.0f - 255.0f * (d / radius + 0.25f);
        out.pixels[k] = static_cast<uint8_t>(std::clamp(std::lround(v), 0L, 255L));
      }
    }
    return out;
  }
};

SdfRenderer::SdfRenderer(const FontSet& fonts, int size_px, int border, float radius) {
  if (size_px < 1 || size_px > 1000) {
    throw TextError("SdfRenderer: size_px must be 1..1000, got " + std::to_string(size_px));
  }
  if (border < 0 || border > 64) {
    throw TextError("SdfRenderer: border must be 0..64 pixels, got " + std::to_string(border));
  }
  if (!(radius >= 1 && radius <= 64)) {
    throw TextError("SdfRenderer: radius must be 1..64 pixels, got " + std::to_string(radius));
  }
  impl_ = std::make_unique<Impl>(fonts, size_px, border, radius);
}

SdfRenderer::~SdfRenderer() = default;

int SdfRenderer::size_px() const {
  return impl_->size_px;
}
int SdfRenderer::border() const {
  return impl_->border;
}
float SdfRenderer::radius() const {
  return impl_->radius;
}
const FontSet& SdfRenderer::fonts() const {
  return impl_->fonts;
}

SdfGlyph SdfRenderer::glyph(uint16_t font, uint32_t glyph_id) const {
  std::lock_guard lock(impl_->mutex);
  return impl_->render(font, glyph_id);
}

std::optional<SdfGlyph> SdfRenderer::codepoint(char32_t c, uint32_t* glyph_id,
                                               uint16_t* font) const {
  const int index = impl_->fonts.font_for(c);
  if (index < 0) return std::nullopt;
  const auto f = static_cast<uint16_t>(index);
  std::lock_guard lock(impl_->mutex);
  const uint32_t id = impl_->faces.glyph_index(f, c);
  if (glyph_id != nullptr) *glyph_id = id;
  if (font != nullptr) *font = f;
  return impl_->render(f, id);
}

int SdfRenderer::ascender_px(uint16_t font) const {
  std::lock_guard lock(impl_->mutex);
  if (font >= impl_->faces.size()) {
    throw TextError("SdfRenderer: font " + std::to_string(font) + " is not in the chain");
  }
  return impl_->faces.ascender_px(font);
}

}  // namespace globe::text
