// lib/text: the font chain, shaping against Debian's hb-shape (the same
// HarfBuzz on the same font files), SDF glyphs against FreeType's own glyph
// boxes, the atlas's packing, and glyph PBFs decoded by a protobuf reader
// written here from the format (not protozero, which wrote them).
#include <ft2build.h>
#include FT_FREETYPE_H
#include FT_BBOX_H
#include FT_MODULE_H
#include FT_OUTLINE_H
#include <unistd.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <random>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "text/font_set.hpp"
#include "text/glyph_atlas.hpp"
#include "text/glyph_pbf.hpp"
#include "text/sdf_glyph.hpp"
#include "text/shaping.hpp"

namespace {

using namespace globe::text;

const std::string kNoto = "/usr/share/fonts/truetype/noto/";
const std::string kDejaVu = "/usr/share/fonts/truetype/dejavu/";

// Debian's chain, built once (it reads every font's character map).
const FontSet& debian_fonts() {
  static const FontSet fonts = FontSet::debian();
  return fonts;
}

int index_of(const FontSet& fonts, const std::string& path) {
  for (size_t i = 0; i < fonts.size(); ++i) {
    if (fonts.path(i) == path) return static_cast<int>(i);
  }
  return -1;
}

std::string run(const std::string& command) {
  std::string out;
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return out;
  char buffer[4096];
  size_t n = 0;
  while ((n = fread(buffer, 1, sizeof buffer, pipe)) > 0)
    out.append(buffer, n);
  pclose(pipe);
  return out;
}

bool have_hb_shape() {
  return std::system("command -v hb-shape >/dev/null 2>&1") == 0;
}

// hb-shape's glyph ids for `text` in `font`, in its (visual) output order.
std::vector<uint32_t> hb_shape_ids(const std::string& font, const std::string& text) {
  const std::string out =
      run("hb-shape --no-glyph-names --no-positions --no-clusters '" + font + "' '" + text + "'");
  std::vector<uint32_t> ids;
  const size_t open = out.find('['), close = out.find(']');
  if (open == std::string::npos || close == std::string::npos) return ids;
  std::string list = out.substr(open + 1, close - open - 1);
  for (size_t at = 0; at <= list.size();) {
    const size_t bar = std::min(list.find('|', at), list.size());
    ids.push_back(static_cast<uint32_t>(std::stoul(list.substr(at, bar - at))));
    at = bar + 1;
  }
  return ids;
}

std::vector<uint32_t> ids_of(const ShapedText& shaped) {
  std::vector<uint32_t> ids;
  for (const PlacedGlyph& g : shaped.glyphs)
    ids.push_back(g.glyph);
  return ids;
}

// The default chain's shaping of `text` equals hb-shape's for `font`, every
// glyph drawn from that font.
void expect_as_hb_shape(const std::string& font, const std::string& text) {
  const FontSet& fonts = debian_fonts();
  const int index = index_of(fonts, font);
  ASSERT_GE(index, 0) << font << " is not in FontSet::debian()";
  const ShapedText shaped = Shaper(fonts).shape(text, 24);
  for (const PlacedGlyph& g : shaped.glyphs)
    EXPECT_EQ(g.font, index) << text;
  const std::vector<uint32_t> expected = hb_shape_ids(font, text);
  ASSERT_FALSE(expected.empty()) << "hb-shape printed nothing for " << text;
  EXPECT_EQ(ids_of(shaped), expected) << text;
}

// FreeType's own box of a glyph at 24 px, unhinted, in pixels.
struct FtBox {
  double x_min, y_min, x_max, y_max;
  int ascender_px;
};
FtBox freetype_box(const std::string& path, char32_t c) {
  FT_Library library = nullptr;
  FT_Face face = nullptr;
  if (FT_Init_FreeType(&library) != 0) throw std::runtime_error("FT_Init_FreeType");
  if (FT_New_Face(library, path.c_str(), 0, &face) != 0) throw std::runtime_error(path);
  FT_Set_Char_Size(face, 0, 24 * 64, 0, 0);
  FT_Load_Glyph(face, FT_Get_Char_Index(face, c), FT_LOAD_NO_HINTING);
  FT_BBox box{};
  FT_Outline_Get_BBox(&face->glyph->outline, &box);
  const FtBox out{box.xMin / 64.0, box.yMin / 64.0, box.xMax / 64.0, box.yMax / 64.0,
                  static_cast<int>(face->size->metrics.ascender / 64)};
  FT_Done_Face(face);
  FT_Done_FreeType(library);
  return out;
}

// FreeType's own FT_RENDER_MODE_SDF of code point c at 24 px (spread 6: it
// stores 128 + 128 * d / 6, d pixels positive inside, with a 6-pixel
// margin), converted to the SdfGlyph convention and compared with `ours`
// texel by texel. Returns the largest difference.
int max_difference_from_freetype(const std::string& path, char32_t c, const SdfGlyph& ours,
                                 float radius) {
  FT_Library library = nullptr;
  FT_Face face = nullptr;
  if (FT_Init_FreeType(&library) != 0) throw std::runtime_error("FT_Init_FreeType");
  FT_Int spread = 6;
  if (FT_Property_Set(library, "sdf", "spread", &spread) != 0) throw std::runtime_error("spread");
  if (FT_New_Face(library, path.c_str(), 0, &face) != 0) throw std::runtime_error(path);
  FT_Set_Char_Size(face, 0, 24 * 64, 0, 0);
  FT_Load_Glyph(face, FT_Get_Char_Index(face, c), FT_LOAD_NO_HINTING);
  if (FT_Render_Glyph(face->glyph, FT_RENDER_MODE_SDF) != 0) throw std::runtime_error("render");
  const FT_Bitmap& bitmap = face->glyph->bitmap;
  int worst = 0, compared = 0;
  for (int j = 0; j < ours.height; ++j) {
    for (int i = 0; i < ours.width; ++i) {
      const int fi = ours.left + i - face->glyph->bitmap_left;
      const int fj = face->glyph->bitmap_top - (ours.top - j);
      if (fi < 0 || fj < 0 || fi >= static_cast<int>(bitmap.width) ||
          fj >= static_cast<int>(bitmap.rows)) {
        continue;
      }
      const float d = -(bitmap.buffer[fj * bitmap.pitch + fi] - 128.0f) * 6 / 128.0f;
      const long v = std::clamp(std::lround(255 - 255 * (d / radius + 0.25f)), 0L, 255L);
      worst = std::max(
          worst,
          static_cast<int>(std::abs(v - ours.pixels[static_cast<size_t>(j) * ours.width + i])));
      ++compared;
    }
  }
  FT_Done_Face(face);
  FT_Done_FreeType(library);
  // The same box: FreeType's, with our border inside its wider margin.
  EXPECT_EQ(compared, ours.width * ours.height) << "U+" << std::hex << static_cast<uint32_t>(c);
  return worst;
}

// ---- A protobuf reader written from the wire format, for the tests only.

struct PbfField {
  uint32_t number = 0;
  int wire_type = 0;
  uint64_t value = 0;  // varint
  std::string bytes;   // length-delimited
};

std::vector<PbfField> pbf_fields(const std::string& data) {
  std::vector<PbfField> fields;
  size_t at = 0;
  auto varint = [&]() {
    uint64_t value = 0;
    for (int shift = 0; shift < 64; shift += 7) {
      if (at >= data.size()) throw std::runtime_error("varint runs past the end");
      const auto byte = static_cast<uint8_t>(data[at++]);
      value |= static_cast<uint64_t>(byte & 0x7F) << shift;
      if ((byte & 0x80) == 0) return value;
    }
    throw std::runtime_error("varint longer than 10 bytes");
  };
  while (at < data.size()) {
    PbfField field;
    const uint64_t key = varint();
    field.number = static_cast<uint32_t>(key >> 3);
    field.wire_type = static_cast<int>(key & 7);
    if (field.wire_type == 0) {
      field.value = varint();
    } else if (field.wire_type == 2) {
      const uint64_t length = varint();
      if (length > data.size() - at) throw std::runtime_error("bytes run past the end");
      field.bytes = data.substr(at, length);
      at += length;
    } else {
      throw std::runtime_error("unexpected wire type " + std::to_string(field.wire_type));
    }
    fields.push_back(field);
  }
  return fields;
}

int64_t zigzag(uint64_t v) {
  return static_cast<int64_t>(v >> 1) ^ -static_cast<int64_t>(v & 1);
}

struct PbfGlyph {
  uint32_t id = 0, width = 0, height = 0, advance = 0;
  int32_t left = 0, top = 0;
  std::optional<std::string> bitmap;
  std::set<uint32_t> fields;
};
struct PbfStack {
  std::string name, range;
  std::map<uint32_t, PbfGlyph> glyphs;
};

std::vector<PbfStack> decode_glyphs(const std::string& data) {
  std::vector<PbfStack> stacks;
  for (const PbfField& top : pbf_fields(data)) {
    EXPECT_EQ(top.number, 1u);
    PbfStack stack;
    for (const PbfField& f : pbf_fields(top.bytes)) {
      if (f.number == 1) stack.name = f.bytes;
      if (f.number == 2) stack.range = f.bytes;
      if (f.number != 3) continue;
      PbfGlyph glyph;
      for (const PbfField& g : pbf_fields(f.bytes)) {
        glyph.fields.insert(g.number);
        switch (g.number) {
          case 1:
            glyph.id = static_cast<uint32_t>(g.value);
            break;
          case 2:
            glyph.bitmap = g.bytes;
            break;
          case 3:
            glyph.width = static_cast<uint32_t>(g.value);
            break;
          case 4:
            glyph.height = static_cast<uint32_t>(g.value);
            break;
          case 5:
            glyph.left = static_cast<int32_t>(zigzag(g.value));
            break;
          case 6:
            glyph.top = static_cast<int32_t>(zigzag(g.value));
            break;
          case 7:
            glyph.advance = static_cast<uint32_t>(g.value);
            break;
          default:
            ADD_FAILURE() << "unknown glyph field " << g.number;
        }
      }
      stack.glyphs[glyph.id] = glyph;
    }
    stacks.push_back(stack);
  }
  return stacks;
}

struct TempFolder {
  std::filesystem::path path;
  TempFolder() {
    path = std::filesystem::temp_directory_path() /
           ("text_test_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::remove_all(path);
    std::filesystem::create_directories(path);
  }
  ~TempFolder() {
    std::error_code ignored;
    std::filesystem::remove_all(path, ignored);
  }
};

// ---- FontSet

TEST(FontSet, DebianChainStartsWithNotoSansAndEndsWithDejaVu) {
  const FontSet& fonts = debian_fonts();
  ASSERT_GE(fonts.size(), 2u);
  EXPECT_EQ(fonts.path(0), kNoto + "NotoSans-Regular.ttf");
  EXPECT_EQ(fonts.path(fonts.size() - 1), kDejaVu + "DejaVuSans.ttf");
  EXPECT_EQ(fonts.family(0), "Noto Sans");
  EXPECT_EQ(fonts.fontstack_name(), "Noto Sans Regular");
  EXPECT_EQ(fonts.font_for(U'A'), 0);
  EXPECT_EQ(fonts.path(static_cast<size_t>(fonts.font_for(U'ق'))),
            kNoto + "NotoSansArabic-Regular.ttf");
  EXPECT_EQ(fonts.path(static_cast<size_t>(fonts.font_for(U'न'))),
            kNoto + "NotoSansDevanagari-Regular.ttf");
  EXPECT_EQ(fonts.font_for(0x0378), -1);  // unassigned: no font has it
}

TEST(FontSet, FirstFontComesFirstAndBoldPicksBoldFiles) {
  const FontSet fonts = FontSet::debian(kDejaVu + "DejaVuSans.ttf", true);
  EXPECT_EQ(fonts.path(0), kDejaVu + "DejaVuSans.ttf");
  EXPECT_EQ(fonts.font_for(U'A'), 0);
  EXPECT_EQ(fonts.path(1), kNoto + "NotoSans-Bold.ttf");
  EXPECT_EQ(fonts.path(fonts.size() - 1), kDejaVu + "DejaVuSans-Bold.ttf");
  EXPECT_EQ(fonts.fontstack_name(), "DejaVu Sans Book");
}

TEST(FontSet, UnreadableFilesAreErrorsNamingTheFile) {
  try {
    FontSet::debian("/nonexistent/label.ttf");
    FAIL() << "no TextError";
  } catch (const TextError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/label.ttf"), std::string::npos);
  }
  TempFolder temp;
  const std::string not_a_font = (temp.path / "not_a_font.ttf").string();
  std::ofstream(not_a_font) << "hello";
  try {
    FontSet({not_a_font});
    FAIL() << "no TextError";
  } catch (const TextError& e) {
    EXPECT_NE(std::string(e.what()).find(not_a_font), std::string::npos);
  }
}

// ---- Shaping

TEST(Shaping, ArabicMatchesHbShapeInVisualOrder) {
  if (!have_hb_shape()) GTEST_SKIP() << "hb-shape missing: apt-get install libharfbuzz-bin";
  expect_as_hb_shape(kNoto + "NotoSansArabic-Regular.ttf", "القاهرة");
  const ShapedText shaped = Shaper(debian_fonts()).shape("القاهرة", 24);
  EXPECT_TRUE(shaped.rtl);
  // Visual order: the leftmost glyph is the last letter (the last UTF-8 bytes).
  ASSERT_FALSE(shaped.glyphs.empty());
  EXPECT_GT(shaped.glyphs.front().cluster, shaped.glyphs.back().cluster);
  EXPECT_GT(shaped.width, 0);
}

TEST(Shaping, DevanagariMatchesHbShape) {
  if (!have_hb_shape()) GTEST_SKIP() << "hb-shape missing: apt-get install libharfbuzz-bin";
  expect_as_hb_shape(kNoto + "NotoSansDevanagari-Regular.ttf", "नई दिल्ली");
}

TEST(Shaping, LatinLigatureAndKerningMatchHbShape) {
  if (!have_hb_shape()) GTEST_SKIP() << "hb-shape missing: apt-get install libharfbuzz-bin";
  expect_as_hb_shape(kNoto + "NotoSans-Regular.ttf", "Office AVATAR");
  const Shaper shaper(debian_fonts());
  EXPECT_LT(shaper.shape("office", 24).glyphs.size(), 6u);  // the ffi ligature
  const float a_alone = shaper.shape("A", 24).width;
  const ShapedText av = shaper.shape("AV", 24);
  ASSERT_EQ(av.glyphs.size(), 2u);
  EXPECT_LT(av.glyphs[0].advance, a_alone - 0.1f);  // kerned
  EXPECT_FLOAT_EQ(av.glyphs[1].x, av.glyphs[0].advance);
  EXPECT_FALSE(av.rtl);
  EXPECT_GT(av.ascent, 10);
  EXPECT_GT(av.descent, 2);
}

TEST(Shaping, MixedScriptsTakeGlyphsFromSeveralFontsInVisualOrder) {
  const FontSet& fonts = debian_fonts();
  const std::string text = "Zürich / Москва / القاهرة";
  const ShapedText shaped = Shaper(fonts).shape(text, 24);
  std::set<uint16_t> used;
  for (const PlacedGlyph& g : shaped.glyphs) {
    used.insert(g.font);
    EXPECT_NE(g.glyph, 0u) << "notdef at byte " << g.cluster;
    EXPECT_LT(g.cluster, text.size());
  }
  EXPECT_GE(used.size(), 2u);
  EXPECT_FALSE(shaped.rtl);  // the first strong character is Latin
  // Left to right: Zürich first, Cairo's glyphs at the right end.
  ASSERT_FALSE(shaped.glyphs.empty());
  EXPECT_EQ(shaped.glyphs.front().cluster, 0u);
  const uint32_t cairo = static_cast<uint32_t>(text.find("القاهرة"));
  EXPECT_GE(shaped.glyphs.back().cluster, cairo);
  for (size_t i = 1; i < shaped.glyphs.size(); ++i) {
    if (shaped.glyphs[i - 1].cluster >= cairo) {  // Cairo right to left
      EXPECT_LE(shaped.glyphs[i].cluster, shaped.glyphs[i - 1].cluster);
    }
  }
  float total = 0;
  for (const PlacedGlyph& g : shaped.glyphs)
    total += g.advance;
  EXPECT_NEAR(shaped.width, total, 1e-3);
}

TEST(Shaping, RightToLeftParagraphPutsItsLatinRunOnTheLeft) {
  // "Shalom World": a Hebrew paragraph; its runs right to left, so "World"
  // is drawn first (leftmost), in its own left-to-right order.
  const std::string text = "שלום World";
  const ShapedText shaped = Shaper(debian_fonts()).shape(text, 24);
  EXPECT_TRUE(shaped.rtl);
  const auto world = static_cast<uint32_t>(text.find("World"));
  ASSERT_GE(shaped.glyphs.size(), 10u);
  for (size_t i = 0; i < 5; ++i)
    EXPECT_EQ(shaped.glyphs[i].cluster, world + i);
  EXPECT_EQ(shaped.glyphs.back().cluster, 0u);  // the first Hebrew letter, rightmost
}

TEST(Shaping, RandomBytesNeverCrash) {
  const Shaper shaper(debian_fonts());
  std::mt19937 random(7);
  for (int n = 0; n < 300; ++n) {
    std::string bytes(random() % 24, '\0');
    for (char& b : bytes)
      b = static_cast<char>(random() & 0xFF);
    const ShapedText shaped = shaper.shape(bytes, 12);
    for (const PlacedGlyph& g : shaped.glyphs) {
      ASSERT_LT(g.cluster, bytes.size());
      ASSERT_LT(g.font, debian_fonts().size());
    }
  }
}

TEST(Shaping, CharacterNoFontHasIsTheFirstFontsNotdef) {
  const FontSet& fonts = debian_fonts();
  ASSERT_EQ(fonts.font_for(0x0378), -1);
  const ShapedText shaped = Shaper(fonts).shape("a\xCD\xB8z", 24);  // U+0378
  ASSERT_EQ(shaped.glyphs.size(), 3u);
  EXPECT_EQ(shaped.glyphs[1].font, 0);
  EXPECT_EQ(shaped.glyphs[1].glyph, 0u);
  EXPECT_EQ(shaped.glyphs[1].cluster, 1u);
  EXPECT_NE(shaped.glyphs[2].glyph, 0u);
}

TEST(Shaping, InvalidUtf8BecomesReplacementCharacters) {
  const Shaper shaper(debian_fonts());
  const ShapedText replacement = shaper.shape("\xEF\xBF\xBD", 24);  // U+FFFD itself
  ASSERT_EQ(replacement.glyphs.size(), 1u);
  for (const std::string bad : {"\xFF", "\xC3", "\xE2\x82", "\xED\xA0\x80", "\xC0\xAF"}) {
    const ShapedText shaped = shaper.shape(bad, 24);
    ASSERT_FALSE(shaped.glyphs.empty());
    for (const PlacedGlyph& g : shaped.glyphs) {
      EXPECT_EQ(g.glyph, replacement.glyphs[0].glyph);
      EXPECT_EQ(g.font, replacement.glyphs[0].font);
      EXPECT_LT(g.cluster, bad.size());
    }
  }
  const std::string mixed =
      "ok\xF4\x90\x80\x80\xFE"
      "done\xE2";
  const ShapedText shaped = shaper.shape(mixed, 24);
  EXPECT_GE(shaped.glyphs.size(), 7u);
  EXPECT_TRUE(shaper.shape("", 24).glyphs.empty());
  EXPECT_THROW(shaper.shape("a", 0), TextError);
}

// ---- SDF glyphs

TEST(Sdf, OHasAHoleInsideARing) {
  const SdfRenderer sdf(debian_fonts());
  uint32_t id = 0;
  uint16_t font = 99;
  const std::optional<SdfGlyph> o = sdf.codepoint(U'O', &id, &font);
  ASSERT_TRUE(o);
  EXPECT_EQ(font, 0);
  EXPECT_NE(id, 0u);
  ASSERT_GT(o->width, 10);
  ASSERT_EQ(o->pixels.size(), static_cast<size_t>(o->width) * static_cast<size_t>(o->height));
  auto at = [&](int x, int y) { return o->pixels[static_cast<size_t>(y) * o->width + x]; };
  const int cy = o->height / 2;
  EXPECT_LT(at(o->width / 2, cy), 191) << "the hole is outside";
  int ring = 0;
  for (int x = 0; x < o->width; ++x)
    ring = std::max<int>(ring, at(x, cy));
  EXPECT_GT(ring, 191) << "the ring is inside";
  // The border is outside, the corners far outside.
  for (int x = 0; x < o->width; ++x) {
    EXPECT_LT(at(x, 0), 128);
    EXPECT_LT(at(x, o->height - 1), 128);
  }
  for (int y = 0; y < o->height; ++y) {
    EXPECT_LT(at(0, y), 128);
    EXPECT_LT(at(o->width - 1, y), 128);
  }
  EXPECT_LT(at(0, 0), 64);

  // FreeType's box of the glyph, on the pixel grid, plus the border.
  const FtBox box = freetype_box(kNoto + "NotoSans-Regular.ttf", U'O');
  const int box_w = static_cast<int>(std::ceil(box.x_max) - std::floor(box.x_min));
  const int box_h = static_cast<int>(std::ceil(box.y_max) - std::floor(box.y_min));
  EXPECT_NEAR(o->width, box_w + 2 * sdf.border(), 1);
  EXPECT_NEAR(o->height, box_h + 2 * sdf.border(), 1);
  EXPECT_NEAR(o->left, std::floor(box.x_min) - sdf.border(), 1);
  EXPECT_NEAR(o->top, std::ceil(box.y_max) + sdf.border(), 1);
  EXPECT_NEAR(o->advance, 24 * 0.6, 24 * 0.2);
}

// FreeType's renderer stores 1/21 px steps, so a level or two of rounding
// apart. (It gets the sign wrong at some sharp corners — one texel of
// Noto Sans 'M', most of U+2E4E — so these glyphs are ones it renders right.)
TEST(Sdf, AgreesWithFreetypesSdfRenderer) {
  const FontSet& fonts = debian_fonts();
  const SdfRenderer sdf(fonts);
  for (const char32_t c : {U'O', U'a', U'g', U'&', U'@', U'ق', U'न', U'ж', U'ß'}) {
    uint16_t font = 0;
    const std::optional<SdfGlyph> glyph = sdf.codepoint(c, nullptr, &font);
    ASSERT_TRUE(glyph);
    EXPECT_LE(max_difference_from_freetype(fonts.path(font), c, *glyph, sdf.radius()), 4)
        << "U+" << std::hex << static_cast<uint32_t>(c);
  }
}

TEST(Sdf, OutlineSitsAtTheCutoff) {
  // 'l' is a vertical bar: along its middle row the field rises to the
  // outline's 191 from the left, so some texel pair brackets 191.
  const SdfRenderer sdf(debian_fonts());
  const std::optional<SdfGlyph> l = sdf.codepoint(U'l');
  ASSERT_TRUE(l);
  const int y = l->height / 2;
  int below = -1;
  for (int x = 0; x + 1 < l->width; ++x) {
    const int a = l->pixels[static_cast<size_t>(y) * l->width + x];
    const int b = l->pixels[static_cast<size_t>(y) * l->width + x + 1];
    if (a < 191 && b >= 191) below = x;
  }
  ASSERT_GE(below, 0);
  // Neighbouring texels, one pixel apart, differ by about 255 / radius.
  const int a = l->pixels[static_cast<size_t>(y) * l->width + below];
  const int b = l->pixels[static_cast<size_t>(y) * l->width + below + 1];
  EXPECT_NEAR(b - a, 255 / 8.0, 6);
}

TEST(Sdf, SpaceIsBlankWithAnAdvance) {
  const SdfRenderer sdf(debian_fonts());
  const std::optional<SdfGlyph> space = sdf.codepoint(U' ');
  ASSERT_TRUE(space);
  EXPECT_EQ(space->width, 0);
  EXPECT_EQ(space->height, 0);
  EXPECT_TRUE(space->pixels.empty());
  EXPECT_GT(space->advance, 3);
  EXPECT_FALSE(sdf.codepoint(0x0378));
  EXPECT_THROW(sdf.glyph(0, 1000000), TextError);
  EXPECT_THROW(SdfRenderer(debian_fonts(), 24, 100), TextError);
}

// ---- Atlas

TEST(Atlas, SameGlyphTwiceIsTheSameEntry) {
  const SdfRenderer sdf(debian_fonts());
  GlyphAtlas atlas(sdf, 256, 256);
  uint32_t id = 0;
  uint16_t font = 0;
  const SdfGlyph a = *sdf.codepoint(U'A', &id, &font);
  const GlyphAtlas::Entry* first = atlas.get(font, id);
  ASSERT_NE(first, nullptr);
  EXPECT_EQ(atlas.get(font, id), first);
  EXPECT_EQ(atlas.glyph_count(), 1u);
  EXPECT_EQ(first->width, a.width);
  EXPECT_EQ(first->height, a.height);
  EXPECT_EQ(first->left, a.left);
  EXPECT_EQ(first->top, a.top);
  for (int y = 0; y < a.height; ++y) {
    for (int x = 0; x < a.width; ++x) {
      ASSERT_EQ(atlas.pixels()[static_cast<size_t>(first->y + y) * 256 + first->x + x],
                a.pixels[static_cast<size_t>(y) * a.width + x]);
    }
  }
  const auto [y0, y1] = atlas.dirty_rows();
  EXPECT_LE(y0, first->y);
  EXPECT_GE(y1, first->y + first->height);
  atlas.clear_dirty();
  EXPECT_EQ(atlas.dirty_rows().first, atlas.dirty_rows().second);
  atlas.get(font, id);  // found again: nothing new to upload
  EXPECT_EQ(atlas.dirty_rows().first, atlas.dirty_rows().second);
}

TEST(Atlas, EntriesDoNotOverlap) {
  const FontSet& fonts = debian_fonts();
  const SdfRenderer sdf(fonts);
  GlyphAtlas atlas(sdf, 256, 256);
  const Shaper shaper(fonts);
  std::vector<const GlyphAtlas::Entry*> entries;
  for (const PlacedGlyph& g :
       shaper.shape("ABCDEFGHIJKLMNOPQRSTUVWXYZ abcdefghijklmnopqrstuvwxyz 0123456789 القاهرة", 24)
           .glyphs) {
    const GlyphAtlas::Entry* e = atlas.get(g.font, g.glyph);
    ASSERT_NE(e, nullptr);
    if (e->width > 0 && std::find(entries.begin(), entries.end(), e) == entries.end()) {
      entries.push_back(e);
    }
  }
  EXPECT_GT(entries.size(), 60u);
  for (size_t i = 0; i < entries.size(); ++i) {
    const GlyphAtlas::Entry& a = *entries[i];
    EXPECT_GE(a.x, 0);
    EXPECT_GE(a.y, 0);
    EXPECT_LE(a.x + a.width, atlas.width());
    EXPECT_LE(a.y + a.height, atlas.height());
    for (size_t j = i + 1; j < entries.size(); ++j) {
      const GlyphAtlas::Entry& b = *entries[j];
      // With the one pixel of padding between them.
      const bool apart = a.x + a.width + 1 <= b.x || b.x + b.width + 1 <= a.x ||
                         a.y + a.height + 1 <= b.y || b.y + b.height + 1 <= a.y;
      EXPECT_TRUE(apart) << i << " and " << j;
    }
  }
}

TEST(Atlas, FullAtlasReturnsNull) {
  const SdfRenderer sdf(debian_fonts());
  GlyphAtlas atlas(sdf, 48, 48);
  const GlyphAtlas::Entry* kept = nullptr;
  uint32_t kept_id = 0;
  size_t placed = 0;
  bool full = false;
  for (char32_t c = U'A'; c <= U'Z' && !full; ++c) {
    uint32_t id = 0;
    uint16_t font = 0;
    ASSERT_TRUE(sdf.codepoint(c, &id, &font));
    const GlyphAtlas::Entry* e = atlas.get(font, id);
    if (e == nullptr) {
      full = true;
    } else {
      ++placed;
      if (kept == nullptr) kept = e, kept_id = id;
    }
  }
  EXPECT_TRUE(full);
  EXPECT_GT(placed, 0u);
  EXPECT_EQ(atlas.glyph_count(), placed);
  EXPECT_EQ(atlas.get(0, kept_id), kept);  // what was placed stays
}

// ---- Glyph PBFs

TEST(GlyphPbf, BasicLatinDecodesAsFontnikWritesIt) {
  const FontSet& fonts = debian_fonts();
  const SdfRenderer sdf(fonts);
  const std::string data = glyph_pbf(sdf, fonts.fontstack_name(), 0);
  const std::vector<PbfStack> stacks = decode_glyphs(data);
  ASSERT_EQ(stacks.size(), 1u);
  const PbfStack& stack = stacks[0];
  EXPECT_EQ(stack.name, "Noto Sans Regular");
  EXPECT_EQ(stack.range, "0-255");
  ASSERT_TRUE(stack.glyphs.count(65));
  const PbfGlyph& a = stack.glyphs.at(65);
  EXPECT_EQ(a.fields, (std::set<uint32_t>{1, 2, 3, 4, 5, 6, 7}));
  ASSERT_TRUE(a.bitmap);
  EXPECT_EQ(a.bitmap->size(), (a.width + 6) * (a.height + 6));
  EXPECT_GT(a.advance, 0u);
  EXPECT_EQ(a.advance, static_cast<uint32_t>(std::floor(sdf.codepoint(U'A')->advance)));
  // fontnik: left = the box's left, top = the box's top minus the 24 px
  // ascender (Noto Sans 'A': 17.1 - 26, fontnik's -9, our -8 as we round
  // the box outward), advance truncated.
  const FtBox box = freetype_box(kNoto + "NotoSans-Regular.ttf", U'A');
  EXPECT_NEAR(a.left, std::round(box.x_min), 1);
  EXPECT_NEAR(a.top, std::round(box.y_max) - box.ascender_px, 1);
  EXPECT_NEAR(a.width, std::round(box.x_max) - std::round(box.x_min), 1);
  EXPECT_NEAR(a.height, std::round(box.y_max) - std::round(box.y_min), 1);
  EXPECT_EQ(box.ascender_px, sdf.ascender_px(0));
  EXPECT_LT(a.top, 0);
  // A blank glyph: no bitmap, no size, top = -ascender (as fontnik writes it).
  ASSERT_TRUE(stack.glyphs.count(32));
  const PbfGlyph& space = stack.glyphs.at(32);
  EXPECT_FALSE(space.bitmap);
  EXPECT_EQ(space.width, 0u);
  EXPECT_EQ(space.top, -box.ascender_px);
  EXPECT_GT(space.advance, 0u);
  // MapLibre's reader keeps a glyph only with a bitmap of exactly this size.
  for (const auto& [id, glyph] : stack.glyphs) {
    EXPECT_LE(id, 255u);
    if (glyph.width > 0 && glyph.height > 0) {
      ASSERT_TRUE(glyph.bitmap) << id;
      EXPECT_EQ(glyph.bitmap->size(), (glyph.width + 6) * (glyph.height + 6)) << id;
    }
  }
  EXPECT_FALSE(stack.glyphs.count(0x7F) && stack.glyphs.at(0x7F).bitmap);
  EXPECT_EQ(glyph_pbf(sdf, fonts.fontstack_name(), 0), data);  // deterministic
  EXPECT_THROW(glyph_pbf(sdf, "x", 100), TextError);
  EXPECT_THROW(glyph_pbf(SdfRenderer(fonts, 32), "x", 0), TextError);
}

TEST(GlyphPbf, WritesTheRangesTheChainCovers) {
  const FontSet& fonts = debian_fonts();
  const SdfRenderer sdf(fonts);
  TempFolder temp;
  const size_t files = write_glyph_pbfs(sdf, fonts.fontstack_name(), temp.path.string());
  const std::filesystem::path folder = temp.path / "Noto Sans Regular";
  EXPECT_TRUE(std::filesystem::is_regular_file(folder / "0-255.pbf"));
  ASSERT_TRUE(std::filesystem::is_regular_file(folder / "1536-1791.pbf"));  // Arabic
  EXPECT_FALSE(std::filesystem::exists(folder / "55296-55551.pbf"));        // surrogates
  size_t on_disk = 0;
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    (void)entry;
    ++on_disk;
  }
  EXPECT_EQ(files, on_disk);
  std::ifstream in(folder / "1536-1791.pbf", std::ios::binary);
  const std::string data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::vector<PbfStack> stacks = decode_glyphs(data);
  ASSERT_EQ(stacks.size(), 1u);
  EXPECT_EQ(stacks[0].range, "1536-1791");
  EXPECT_TRUE(stacks[0].glyphs.count(0x0642));  // ق
}

}  // namespace
