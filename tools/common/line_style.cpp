// Line class styles in JSON (see line_style.hpp).
#include "line_style.hpp"

#include <cpl_json.h>
#include <cctype>
#include <iterator>

#include "errors.hpp"

namespace globe {
namespace {

// Distinct, print-safe colours (ColorBrewer Dark2 + Set1), by class id.
const char* const kPalette[] = {"#1b9e77", "#d95f02", "#7570b3", "#e7298a", "#66a61e",
                                "#e6ab02", "#a6761d", "#377eb8", "#e41a1c", "#4daf4a"};

CPLJSONObject load_json(const std::string& json, const std::string& context,
                        CPLJSONObject::Type type, const char* what) {
  CPLJSONDocument doc;
  if (!doc.LoadMemory(json)) throw InputError(context + ": not valid JSON (" + what + ")");
  if (doc.GetRoot().GetType() != type) throw InputError(context + ": expected " + what);
  return doc.GetRoot();
}

double length_of(const CPLJSONObject& v, const std::string& where) {
  const auto t = v.GetType();
  if (t != CPLJSONObject::Type::Integer && t != CPLJSONObject::Type::Long &&
      t != CPLJSONObject::Type::Double)
    throw InputError(where + ": expected a number");
  const double d = v.ToDouble();
  if (!(d >= 0) || d > 10000) throw InputError(where + ": " + std::to_string(d) + " out of range");
  return d;
}

std::string color_of(const CPLJSONObject& v, const std::string& where, bool allow_empty) {
  if (v.GetType() != CPLJSONObject::Type::String) throw InputError(where + ": expected a string");
  const std::string c = v.ToString();
  if ((c.empty() && allow_empty) || is_hex_color(c)) return c;
  throw InputError(where + ": '" + c + "' is not #rrggbb");
}

// Reads the keys present in `o` onto `s`.
void read_style(const CPLJSONObject& o, const std::string& where, LineStyle& s) {
  for (const CPLJSONObject& v : o.GetChildren()) {
    const std::string key = v.GetName(), at = where + " \"" + key + "\"";
    if (key == "color") {
      s.color = color_of(v, at, true);
    } else if (key == "width") {
      s.width = length_of(v, at);
      if (s.width <= 0) throw InputError(at + ": must be positive");
    } else if (key == "unit") {
      const std::string u = v.ToString();
      if (u != "px" && u != "m") throw InputError(at + ": '" + u + "' is not px or m");
      s.width_in_m = u == "m";
    } else if (key == "casing_color") {
      s.casing_color = color_of(v, at, true);
    } else if (key == "casing_width") {
      s.casing_width = length_of(v, at);
    } else if (key == "dash") {
      if (v.GetType() != CPLJSONObject::Type::Array)
        throw InputError(at + ": expected an array of on/off lengths");
      s.dash.clear();
      const CPLJSONArray a = v.ToArray();
      for (int i = 0; i < a.Size(); ++i)
        s.dash.push_back(length_of(a[i], at));
      if (s.dash.size() % 2 != 0 || s.dash.size() > 8)
        throw InputError(at + ": needs 1 to 4 on/off pairs");
      double sum = 0;
      for (double d : s.dash)
        sum += d;
      if (!s.dash.empty() && sum <= 0) throw InputError(at + ": the pattern has zero length");
    } else if (key == "visible") {
      if (v.GetType() != CPLJSONObject::Type::Boolean)
        throw InputError(at + ": expected true/false");
      s.visible = v.ToBool();
    } else if (key != "id" && key != "name" && key != "layer" && key != "features") {
      throw InputError(at +
                       ": unknown key (color, width, unit, casing_color, casing_width, dash, "
                       "visible)");
    }
  }
}

}  // namespace

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
  const CPLJSONArray arr =
      load_json(json, context, CPLJSONObject::Type::Array, "a JSON array of classes").ToArray();
  std::vector<NamedLineStyle> out;
  for (int i = 0; i < arr.Size(); ++i) {
    if (arr[i].GetType() != CPLJSONObject::Type::Object)
      throw InputError(context + ": class " + std::to_string(i) + " is not an object");
    NamedLineStyle c;
    c.name = arr[i].GetString("name");
    read_style(arr[i], context + " class " + std::to_string(i), c.style);
    if (c.style.color.empty()) c.style.color = palette_color(out.size());
    out.push_back(std::move(c));
  }
  return out;
}

void apply_style_json(const std::string& json, const std::string& context,
                      std::vector<NamedLineStyle>& classes) {
  const CPLJSONObject root =
      load_json(json, context, CPLJSONObject::Type::Object, "a JSON object of class name -> style");
  std::vector<bool> named(classes.size(), false);
  const CPLJSONObject* all = nullptr;
  const auto children = root.GetChildren();
  for (const CPLJSONObject& v : children) {
    const std::string name = v.GetName();
    if (v.GetType() != CPLJSONObject::Type::Object)
      throw InputError(context + ": \"" + name + "\" is not an object of style keys");
    if (name == "*") {
      all = &v;
      continue;
    }
    bool found = false;
    for (size_t i = 0; i < classes.size(); ++i)
      if (classes[i].name == name) {
        read_style(v, context + " \"" + name + "\"", classes[i].style);
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
      if (!named[i]) read_style(*all, context + " \"*\"", classes[i].style);
}

}  // namespace globe
