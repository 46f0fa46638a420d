// Glyph PBFs for the styles' labels (see glyphs.hpp).
#include "web/glyphs.hpp"

#include <map>
#include <mutex>

#include "runtime/errors.hpp"
#include "text/font_set.hpp"
#include "text/glyph_pbf.hpp"
#include "text/sdf_glyph.hpp"

namespace globe::web {

struct GlyphSet::Impl {
  // MapLibre's glyph PBFs: 24 px, border 3 (the renderer's defaults).
  explicit Impl(text::FontSet f)
      : fonts(std::move(f)), sdf(fonts), fontstack(fonts.fontstack_name()) {}
  text::FontSet fonts;
  text::SdfRenderer sdf;
  std::string fontstack;
  std::mutex mutex;   // guards `made`
  std::mutex making;  // one range made at a time (the renderer is serial anyway)
  std::map<uint32_t, std::shared_ptr<const std::string>> made;
};

namespace {

text::FontSet debian_fonts() {
  try {
    return text::FontSet::debian();
  } catch (const text::TextError& e) {
    throw InputError(std::string("glyphs: ") + e.what());
  }
}

}  // namespace

GlyphSet::GlyphSet() : impl_(std::make_unique<Impl>(debian_fonts())) {}

GlyphSet::~GlyphSet() = default;

const std::string& GlyphSet::fontstack() const {
  return impl_->fontstack;
}

bool GlyphSet::has_range(uint32_t start) const {
  if (start % 256 != 0 || start > 0xFF00) return false;
  for (char32_t c = start; c < start + 256; ++c)
    if ((c < 0xD800 || c > 0xDFFF) && impl_->fonts.font_for(c) >= 0) return true;
  return false;
}

std::shared_ptr<const std::string> GlyphSet::range(uint32_t start) const {
  if (!has_range(start)) return nullptr;
  auto kept = [&]() -> std::shared_ptr<const std::string> {
    std::lock_guard lock(impl_->mutex);
    const auto it = impl_->made.find(start);
    return it == impl_->made.end() ? nullptr : it->second;
  };
  if (auto pbf = kept()) return pbf;  // a kept range never waits for one being made
  std::lock_guard making(impl_->making);
  if (auto pbf = kept()) return pbf;  // made while this request waited
  std::shared_ptr<const std::string> pbf;
  try {
    pbf = std::make_shared<const std::string>(text::glyph_pbf(impl_->sdf, impl_->fontstack, start));
  } catch (const text::TextError& e) {
    throw InputError(std::string("glyphs: ") + e.what());
  }
  std::lock_guard lock(impl_->mutex);
  impl_->made[start] = pbf;
  return pbf;
}

size_t GlyphSet::write(const std::string& dir) const {
  try {
    return text::write_glyph_pbfs(impl_->sdf, impl_->fontstack, dir);
  } catch (const text::TextError& e) {
    throw OutputError(std::string("glyphs: ") + e.what());
  }
}

}  // namespace globe::web
