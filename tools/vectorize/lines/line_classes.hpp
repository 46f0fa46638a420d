// Style classes of a line package: which class a feature belongs to (its
// layer, or the value of --class-field renamed by --class-map) and each
// class's style (colour, width in px or m, casing, dash), written to the
// package metadata as JSON (docs/lines.md "Classes and styles").
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "runtime/line_style.hpp"

namespace globe {

struct LineClass {
  std::string name;
  std::string layer;  // first layer seen with this class
  LineStyle style;
  uint64_t features = 0;
};

class LineClasses {
 public:
  // class_map: "VALUE=NAME,..." (--class-map); styles: "NAME:key=value,..."
  // (--style, keys color, width, casing, dash). Throws UsageError.
  LineClasses(const std::string& class_map, const std::vector<std::string>& styles);

  // The class of a feature of `layer` whose class field reads `value` ("" =
  // no class field: the layer's name is the class). Assigns ids in order of
  // first appearance.
  uint32_t class_for(const std::string& layer, const std::string& value);
  const std::vector<LineClass>& classes() const { return classes_; }
  // Largest half_extent over all classes, separately for px and m widths.
  double max_half_px() const;
  double max_half_m() const;
  std::string json() const;  // metadata globe:classes
  // The message for the first --style class no feature has ("" if none):
  // a typo would otherwise leave the class unstyled without a word. Call
  // after reading.
  std::string unused_style() const;

 private:
  std::map<std::string, std::string> rename_;
  std::map<std::string, LineStyle> styles_;
  std::map<std::string, uint32_t> ids_;
  std::vector<LineClass> classes_;
};

// Parses one style ("key=value,...") onto `style`; throws UsageError.
void parse_style(const std::string& spec, LineStyle& style, const std::string& context);

}  // namespace globe
