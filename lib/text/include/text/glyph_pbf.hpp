// MapLibre glyph PBFs: a fontstack's code points in ranges of 256, as the
// protobuf MapLibre GL JS / Native load from a style's "glyphs" URL
// "{fontstack}/{range}.pbf", written as node-fontnik writes them so MapLibre
// places our glyphs exactly as it places fontnik's. Glyphs come from
// sdf_glyph.hpp; no protozero types here.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "text/sdf_glyph.hpp"

namespace globe::text {

// MapLibre glyph range `start`..`start`+255 (start a multiple of 256) as the
// protobuf MapLibre loads from "{fontstack}/{start}-{end}.pbf":
//   message glyphs { repeated fontstack stacks = 1; }
//   message fontstack { required string name = 1; required string range = 2;
//                       repeated glyph glyphs = 3; }
//   message glyph { required uint32 id = 1; optional bytes bitmap = 2;
//                   required uint32 width = 3; required uint32 height = 4;
//                   required sint32 left = 5; required sint32 top = 6;
//                   required uint32 advance = 7; }
// The SDF must be rendered at 24 px with border 3 (MapLibre's ONE_EM and
// Glyph::borderSize; TextError otherwise). As node-fontnik writes them
// (its src/glyphs.cpp and RenderSDF in include/mapbox/glyph_foundry_impl.hpp):
//   id       the Unicode code point;
//   bitmap   (width + 6) * (height + 6) bytes, top row first, absent when blank;
//   width, height  the glyph's pixels WITHOUT the border (0 when blank);
//   left     the bitmap's left edge right of the pen, without the border;
//   top      the bitmap's top edge above the baseline, without the border,
//            MINUS the font's ascender at 24 px (FreeType's size metrics,
//            truncated to whole pixels: 26 for Noto Sans), so Noto Sans 'A'
//            has top -8 and a blank glyph -ascender. MapLibre starts a line
//            17 px above the baseline it lays glyphs on (Shaping::yOffset),
//            tuned to these values;
//   advance  whole pixels, truncated (fontnik's horiAdvance / 64).
// fontnik rounds the glyph's box to whole pixels, where we round it outward
// (FreeType's grid box), so our box can be a pixel larger ('A': top -8,
// fontnik's -9); each bitmap's outline sits where its metrics say, so
// MapLibre draws both at the same place.
// Code points no font has, and glyphs MapLibre would reject (a side of 256
// pixels or more, left or top outside -128..127, advance of 256 or more), are
// left out. Deterministic: the same fonts give the same bytes.
std::string glyph_pbf(const SdfRenderer& sdf, const std::string& fontstack, uint32_t start);

// Writes every range of the Basic Multilingual Plane that has at least one glyph
// as DIR/{fontstack}/{start}-{end}.pbf (folders made as needed); returns how
// many files. TextError naming the file when one cannot be written.
size_t write_glyph_pbfs(const SdfRenderer& sdf, const std::string& fontstack,
                        const std::string& dir);

}  // namespace globe::text
