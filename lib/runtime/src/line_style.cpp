// Line class styles in JSON (see line_style.hpp).
#include "runtime/line_style.hpp"

#include <cctype>
#include <filesystem>
#include <iterator>

#include "runtime/errors.hpp"
#include "tileformat/json.hpp"

namespace globe {
namespace {

// Distinct, print-safe colours (ColorBrewer Dark2 + Set1), by class id.
const char* const kPalette[] = {"#1b9e77", "#d95f02", "#7570b3", "#e7298a", "#66a61e",
                                "#e6ab02", "#a6761d", "#377eb8", "#e41a1c", "#4daf4a"};

using tileformat::JsonValue;

JsonValue load_json(const std::string& json, const std::string& context, JsonValue::Type type,
                    const char* what) {
  JsonValue root;
  try {
    root = JsonValue::parse(json);
  } catch (const tileformat::JsonError& e) {
    throw InputError(context + ": not valid JSON (" + what + "; " + e.what() + ")");
  }
  if (root.type() != type) throw InputError(context + ": expected " + what);
  return root;
}

double length_of(const JsonValue& v, const std::string& where) {
  if (!v.is_number()) throw InputError(where + ": expected a number");
  const double d = v.number();
  if (!(d >= 0) || d > 10000) throw InputError(where + ": " + std::to_string(d) + " out of range");
  return d;
}

std::string color_of(const JsonValue& v, const std::string& where, bool allow_empty) {
  if (!v.is_string()) throw InputError(where + ": expected a string");
  const std::string& c = v.string();
  if ((c.empty() && allow_empty) || is_hex_color(c)) return c;
  throw InputError(where + ": '" + c + "' is not #rrggbb (or slope[:FILE], height[:FILE])");
}

// Reads the keys present in `o` onto `s`; colour files named relative to base_dir.
void read_style(const JsonValue& o, const std::string& where, LineStyle& s,
                const std::string& base_dir) {
  for (const auto& [key, v] : o.members()) {
    const std::string at = where + " \"" + key + "\"";
    if (key == "color") {
      if (v.is_string() && parse_line_color_by(v.string(), s, base_dir)) continue;
      s.color = color_of(v, at, true);
      s.color_by.clear();
    } else if (key == "width") {
      s.width = length_of(v, at);
      if (s.width <= 0) throw InputError(at + ": must be positive");
    } else if (key == "unit") {
      const std::string u = v.is_string() ? v.string() : "";
      if (u != "px" && u != "m") throw InputError(at + ": '" + u + "' is not px or m");
      s.width_in_m = u == "m";
    } else if (key == "casing_color") {
      s.casing_color = color_of(v, at, true);
    } else if (key == "casing_width") {
      s.casing_width = length_of(v, at);
    } else if (key == "dash") {
      if (!v.is_array()) throw InputError(at + ": expected an array of on/off lengths");
      s.dash.clear();
      for (const JsonValue& d : v.array())
        s.dash.push_back(length_of(d, at));
      if (s.dash.size() % 2 != 0 || s.dash.size() > 8)
        throw InputError(at + ": needs 1 to 4 on/off pairs");
      double sum = 0;
      for (double d : s.dash)
        sum += d;
      if (!s.dash.empty() && sum <= 0) throw InputError(at + ": the pattern has zero length");
    } else if (key == "opacity") {
      if (!v.is_number() || !(v.number() >= 0 && v.number() <= 1))
        throw InputError(at + ": expected a number from 0 to 1");
      s.opacity = v.number();
    } else if (key == "pattern") {
      if (!v.is_string() || (!v.string().empty() && line_pattern_id(v.string()) < 0))
        throw InputError(at + ": expected \"\" or one of railway, arrows, zigzag, dots");
      s.pattern = v.string();
    } else if (key == "color_by") {  // as globe-vectorize stores "color=slope:FILE"
      if (!v.is_string() || (!v.string().empty() && !parse_line_color_by(v.string(), s, base_dir)))
        throw InputError(at + ": expected \"slope\" or \"height\"");
      if (v.string().empty()) s.color_by.clear();
    } else if (key == "ramp") {
      if (!v.is_string()) throw InputError(at + ": expected a colour file's path");
      s.ramp = v.string().empty() || base_dir.empty() || v.string()[0] == '/'
                   ? v.string()
                   : base_dir + "/" + v.string();
    } else if (key == "pattern_spacing") {
      s.pattern_spacing = length_of(v, at);
    } else if (key == "visible") {
      if (!v.is_bool()) throw InputError(at + ": expected true/false");
      s.visible = v.boolean();
    } else if (key != "id" && key != "name" && key != "layer" && key != "features") {
      throw InputError(at +
                       ": unknown key (color, width, unit, casing_color, casing_width, dash, "
                       "opacity, visible, pattern, pattern_spacing, color_by, ramp)");
    }
  }
}

}  // namespace

bool parse_line_color_by(const std::string& value, LineStyle& s, const std::string& base_dir) {
  const auto colon = value.find(':');
  const std::string by = value.substr(0, colon);
  if (by != "slope" && by != "height") return false;
  s.color_by = by;
  s.ramp.clear();
  if (colon != std::string::npos) {
    s.ramp = value.substr(colon + 1);
    if (!s.ramp.empty() && s.ramp[0] != '/' && !base_dir.empty()) s.ramp = base_dir + "/" + s.ramp;
  }
  return true;
}

int line_pattern_id(const std::string& name) {
  if (name.empty()) return 0;
  for (size_t i = 0; i < std::size(kLinePatterns); ++i)
    if (name == kLinePatterns[i]) return static_cast<int>(i) + 1;
  return -1;
}

double line_pattern_spacing(const LineStyle& s) {
  if (s.pattern_spacing > 0) return s.pattern_spacing;
  // Ties and teeth close together, arrows and dots further apart.
  const int id = line_pattern_id(s.pattern);
  return s.width * (id == 1 ? 2.5 : id == 3 ? 3.0 : id == 4 ? 2.5 : 6.0);
}

const char* palette_color(size_t id) {
  return kPalette[id % std::size(kPalette)];
}

bool is_hex_color(const std::string& c) {
  if (c.size() != 7 || c[0] != '#') return false;
  for (size_t i = 1; i < 7; ++i)
    if (!std::isxdigit(static_cast<unsigned char>(c[i]))) return false;
  return true;
}

std::vector<NamedLineStyle> parse_classes_json(const std::string& json,
                                               const std::string& context) {
  const JsonValue root =
      load_json(json, context, JsonValue::Type::kArray, "a JSON array of classes");
  const std::vector<JsonValue>& arr = root.array();
  std::vector<NamedLineStyle> out;
  for (size_t i = 0; i < arr.size(); ++i) {
    if (!arr[i].is_object())
      throw InputError(context + ": class " + std::to_string(i) + " is not an object");
    NamedLineStyle c;
    if (const JsonValue* name = arr[i].find("name"); name && name->is_string())
      c.name = name->string();
    read_style(arr[i], context + " class " + std::to_string(i), c.style, "");
    if (c.style.color.empty()) c.style.color = palette_color(out.size());
    out.push_back(std::move(c));
  }
  return out;
}

void apply_style_json(const std::string& json, const std::string& context,
                      std::vector<NamedLineStyle>& classes) {
  const std::string base_dir = std::filesystem::path(context).parent_path().string();
  const JsonValue root =
      load_json(json, context, JsonValue::Type::kObject, "a JSON object of class name -> style");
  std::vector<bool> named(classes.size(), false);
  const JsonValue* all = nullptr;
  for (const auto& [name, v] : root.members()) {
    if (!v.is_object())
      throw InputError(context + ": \"" + name + "\" is not an object of style keys");
    if (name == "*") {
      all = &v;
      continue;
    }
    bool found = false;
    for (size_t i = 0; i < classes.size(); ++i)
      if (classes[i].name == name) {
        read_style(v, context + " \"" + name + "\"", classes[i].style, base_dir);
        named[i] = found = true;
      }
    if (!found) {
      std::string names;
      for (const NamedLineStyle& c : classes)
        names += (names.empty() ? "" : ", ") + c.name;
      throw InputError(context + ": no class \"" + name + "\" in the package (classes: " + names +
                       ")");
    }
  }
  if (all)
    for (size_t i = 0; i < classes.size(); ++i)
      if (!named[i]) read_style(*all, context + " \"*\"", classes[i].style, base_dir);
}

}  // namespace globe
