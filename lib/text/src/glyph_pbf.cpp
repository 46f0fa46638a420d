// MapLibre glyph PBFs, written with protozero (called from here only). The
// metrics follow node-fontnik (src/glyphs.cpp, RenderSDF of
// sdf-glyph-foundry's glyph_foundry_impl.hpp), which MapLibre's shaping is
// tuned to: `top` is the glyph's top edge minus the font's 24 px ascender,
// `advance` the unhinted advance truncated. MapLibre Native's reader
// (src/mbgl/text/glyph_pbf.cpp) drops a glyph whose bitmap is not exactly
// (width + 6) * (height + 6) bytes or whose metrics are out of its ranges, so
// those are checked here rather than written.
#include "text/glyph_pbf.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <protozero/pbf_writer.hpp>

namespace globe::text {
namespace {

constexpr int kPbfSizePx = 24;  // MapLibre's ONE_EM
constexpr int kPbfBorder = 3;   // MapLibre's Glyph::borderSize

void check_renderer(const SdfRenderer& sdf) {
  if (sdf.size_px() != kPbfSizePx || sdf.border() != kPbfBorder) {
    throw TextError("glyph PBFs need SDF glyphs of 24 px with a border of 3 (MapLibre's), got " +
                    std::to_string(sdf.size_px()) + " px and " + std::to_string(sdf.border()) +
                    "; make the SdfRenderer with the defaults");
  }
}

bool is_code_point(char32_t c) {
  return c < 0xD800 || c > 0xDFFF;
}

}  // namespace

std::string glyph_pbf(const SdfRenderer& sdf, const std::string& fontstack, uint32_t start) {
  check_renderer(sdf);
  if (start % 256 != 0 || start > 0x10FF00) {
    throw TextError("glyph_pbf: range start " + std::to_string(start) +
                    " is not a multiple of 256 within Unicode");
  }
  const uint32_t end = start + 255;
  std::string data;
  protozero::pbf_writer glyphs(data);
  {
    protozero::pbf_writer stack(glyphs, 1);
    stack.add_string(1, fontstack);
    stack.add_string(2, std::to_string(start) + "-" + std::to_string(end));
    for (uint32_t c = start; c <= end; ++c) {
      if (!is_code_point(c)) continue;
      uint16_t font = 0;
      const std::optional<SdfGlyph> glyph = sdf.codepoint(c, nullptr, &font);
      if (!glyph) continue;
      const bool blank = glyph->width == 0 || glyph->height == 0;
      const int width = blank ? 0 : glyph->width - 2 * kPbfBorder;
      const int height = blank ? 0 : glyph->height - 2 * kPbfBorder;
      const int left = blank ? 0 : glyph->left + kPbfBorder;
      const int top = (blank ? 0 : glyph->top - kPbfBorder) - sdf.ascender_px(font);
      const double advance = std::floor(glyph->advance);
      if (width >= 256 || height >= 256 || left < -128 || left >= 128 || top < -128 || top >= 128 ||
          advance < 0 || advance >= 256) {
        continue;  // MapLibre would drop it
      }
      protozero::pbf_writer out(stack, 3);
      out.add_uint32(1, c);
      if (!blank) {
        out.add_bytes(2, reinterpret_cast<const char*>(glyph->pixels.data()), glyph->pixels.size());
      }
      out.add_uint32(3, static_cast<uint32_t>(width));
      out.add_uint32(4, static_cast<uint32_t>(height));
      out.add_sint32(5, left);
      out.add_sint32(6, top);
      out.add_uint32(7, static_cast<uint32_t>(advance));
    }
  }
  return data;
}

size_t write_glyph_pbfs(const SdfRenderer& sdf, const std::string& fontstack,
                        const std::string& dir) {
  check_renderer(sdf);
  const std::filesystem::path folder = std::filesystem::path(dir) / fontstack;
  std::error_code error;
  std::filesystem::create_directories(folder, error);
  if (error) {
    throw TextError(folder.string() + ": cannot make the folder (" + error.message() +
                    "); pick a writable output folder");
  }
  const FontSet& fonts = sdf.fonts();
  size_t files = 0;
  for (uint32_t start = 0; start < 0x10000; start += 256) {
    bool any = false;
    for (uint32_t c = start; c < start + 256 && !any; ++c) {
      any = is_code_point(c) && fonts.font_for(c) >= 0;
    }
    if (!any) continue;
    const std::string data = glyph_pbf(sdf, fontstack, start);
    const std::filesystem::path file =
        folder / (std::to_string(start) + "-" + std::to_string(start + 255) + ".pbf");
    std::ofstream out(file, std::ios::binary | std::ios::trunc);
    out.write(data.data(), static_cast<std::streamsize>(data.size()));
    out.close();
    if (!out) {
      throw TextError(file.string() +
                      ": cannot write the glyph PBF; check the disk and the "
                      "folder's permissions");
    }
    ++files;
  }
  return files;
}

}  // namespace globe::text
