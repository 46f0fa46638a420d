// The style of a line class (colour, width in px or m, casing, dash), as
// globe-vectorize writes it into a line package's metadata (`globe:classes`,
// tileformat §7.4) and as globe-view reads it back, optionally overridden by
// a style file (docs/viewer.md "Style files").
#pragma once

#include <string>
#include <vector>

namespace globe {

struct LineStyle {
  std::string color;  // "#rrggbb"; "" = from the default palette
  double width = 1.5;
  bool width_in_m = false;   // false: pixels
  std::string casing_color;  // "" = no casing
  double casing_width = 0;   // on each side, in the unit of `width`
  std::vector<double> dash;  // on/off lengths in the unit of `width`; empty = solid
  bool visible = true;       // style files may hide a class
  double opacity = 1;        // 0..1: how much of what lies under the line shows through
  // A procedural pattern drawn per pixel instead of the plain fill
  // (docs/viewer.md "Line patterns"): "" (none), "railway", "arrows" (along
  // the line's vertex order), "zigzag" or "dots"; one motif every
  // `pattern_spacing` (the width's unit; 0 = the pattern's default).
  std::string pattern;
  double pattern_spacing = 0;
  // Colour by the ground under the line, per pixel (docs/viewer.md "Lines
  // coloured by the ground"): "" (the plain colour), "slope" (degrees) or
  // "height" (metres), through the gdaldem colour file `ramp` ("" =
  // built-in: cream to red over 0..45 degrees, hypsometric over the
  // terrain's heights).
  std::string color_by;
  std::string ramp;
  // Half the drawn width including casing, in the width's unit.
  double half_extent() const { return width / 2 + (casing_color.empty() ? 0 : casing_width); }
};

struct NamedLineStyle {
  std::string name;
  LineStyle style;
};

// The patterns LineStyle::pattern names, by id (1..4; 0 = none), and the
// id of a name (-1 for an unknown one).
inline constexpr const char* kLinePatterns[] = {"railway", "arrows", "zigzag", "dots"};
int line_pattern_id(const std::string& name);
// Spacing of the motifs in the width's unit: the style's, or the pattern's
// default (a multiple of the width).
double line_pattern_spacing(const LineStyle& s);

// A colour expression "slope", "height", "slope:FILE" or "height:FILE" into
// s.color_by and s.ramp (a relative FILE taken from base_dir when given);
// false (s unchanged) for anything else.
bool parse_line_color_by(const std::string& value, LineStyle& s, const std::string& base_dir = "");

// The default palette colour of class `id`.
const char* palette_color(size_t id);
bool is_hex_color(const std::string& c);

// `globe:classes` (a JSON array, by class id) -> styles; empty colours take
// the palette. Throws InputError naming `context`.
std::vector<NamedLineStyle> parse_classes_json(const std::string& json, const std::string& context);

// Applies a style file on top of `classes`: a JSON object whose keys are
// class names, or "*" for every class a key does not name, each holding any
// of "color", "width", "unit" ("px"|"m"), "casing_color", "casing_width",
// "dash" (array of on/off lengths), "opacity" (0..1), "visible", "pattern"
// and "pattern_spacing". Throws InputError naming
// `context` (the file) and the key.
void apply_style_json(const std::string& json, const std::string& context,
                      std::vector<NamedLineStyle>& classes);

}  // namespace globe
