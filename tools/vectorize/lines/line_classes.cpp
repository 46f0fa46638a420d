// Style classes (see line_classes.hpp).
#include "lines/line_classes.hpp"

#include <cstdio>
#include <sstream>

#include "runtime/cli_args.hpp"
#include "runtime/errors.hpp"
#include "tileformat/json.hpp"

namespace globe {
namespace {

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> out;
  std::string cur;
  std::istringstream in(s);
  while (std::getline(in, cur, sep))
    out.push_back(cur);
  return out;
}

// "3", "3px" or "12m" -> value; sets *in_m when given.
double parse_length(const std::string& v, const std::string& context, bool* in_m) {
  std::string num = v;
  bool m = false;
  if (num.size() > 2 && num.compare(num.size() - 2, 2, "px") == 0) {
    num.resize(num.size() - 2);
  } else if (!num.empty() && num.back() == 'm') {
    num.pop_back();
    m = true;
  }
  const double d = CliArgs::to_double(context, num);
  if (!(d >= 0) || d > 10000) throw UsageError(context + ": length '" + v + "' out of range");
  if (in_m) *in_m = m;
  return d;
}

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

}  // namespace

void parse_style(const std::string& spec, LineStyle& s, const std::string& context) {
  for (const std::string& kv : split(spec, ',')) {
    const auto eq = kv.find('=');
    if (eq == std::string::npos)
      throw UsageError(context + ": '" + kv +
                       "' is not key=value (keys: color, width, casing, dash, opacity, pattern)");
    const std::string key = kv.substr(0, eq), value = kv.substr(eq + 1);
    if (key == "color") {
      if (parse_line_color_by(value, s)) continue;  // by the ground under the line
      if (!is_hex_color(value))
        throw UsageError(context + ": color '" + value +
                         "' is not #rrggbb, slope[:RAMP.txt] or height[:RAMP.txt]");
      s.color = value;
    } else if (key == "width") {
      s.width = parse_length(value, context + " width", &s.width_in_m);
      if (s.width <= 0) throw UsageError(context + ": width must be positive");
    } else if (key == "casing") {  // #rrggbb@WIDTH
      const auto at = value.find('@');
      s.casing_color = value.substr(0, at);
      if (!is_hex_color(s.casing_color))
        throw UsageError(context + ": casing '" + value + "' is not #rrggbb@WIDTH");
      s.casing_width =
          at == std::string::npos ? 1 : parse_length(value.substr(at + 1), context, nullptr);
    } else if (key == "dash") {  // on+off[+on+off...]
      s.dash.clear();
      for (const std::string& d : split(value, '+'))
        s.dash.push_back(parse_length(d, context + " dash", nullptr));
      if (s.dash.size() % 2 != 0 || s.dash.empty())
        throw UsageError(context + ": dash needs on+off pairs, e.g. dash=6+3");
    } else if (key == "opacity") {
      s.opacity = CliArgs::to_double(context + " opacity", value);
      if (!(s.opacity >= 0 && s.opacity <= 1))
        throw UsageError(context + ": opacity '" + value + "' is not between 0 and 1");
    } else if (key == "pattern") {  // NAME[@SPACING]
      const auto at = value.find('@');
      s.pattern = value.substr(0, at);
      if (line_pattern_id(s.pattern) <= 0)
        throw UsageError(context + ": pattern '" + s.pattern +
                         "' is not railway, arrows, zigzag or dots");
      s.pattern_spacing =
          at == std::string::npos ? 0 : parse_length(value.substr(at + 1), context, nullptr);
    } else {
      throw UsageError(context + ": unknown style key '" + key +
                       "' (keys: color, width, casing, dash, opacity, pattern)");
    }
  }
}

LineClasses::LineClasses(const std::string& class_map, const std::vector<std::string>& styles) {
  if (!class_map.empty()) {
    for (const std::string& entry : split(class_map, ',')) {
      const auto eq = entry.find('=');
      if (eq == std::string::npos || eq == 0 || eq + 1 == entry.size())
        throw UsageError("--class-map: '" + entry + "' is not VALUE=NAME");
      rename_[entry.substr(0, eq)] = entry.substr(eq + 1);
    }
  }
  for (const std::string& st : styles) {
    const auto colon = st.find(':');
    if (colon == std::string::npos || colon == 0)
      throw UsageError("--style: '" + st + "' is not CLASS:key=value,...");
    parse_style(st.substr(colon + 1), styles_[st.substr(0, colon)],
                "--style " + st.substr(0, colon));
  }
}

uint32_t LineClasses::class_for(const std::string& layer, const std::string& value) {
  std::string name = value.empty() ? layer : value;
  if (auto it = rename_.find(name); it != rename_.end()) name = it->second;
  if (auto it = ids_.find(name); it != ids_.end()) {
    ++classes_[it->second].features;
    return it->second;
  }
  if (classes_.size() >= 65535)
    throw UsageError(
        "more than 65535 classes; use --class-map to group values or drop --class-field");
  const uint32_t id = static_cast<uint32_t>(classes_.size());
  LineClass c{name, layer, {}, 1};
  if (auto it = styles_.find(name); it != styles_.end()) c.style = it->second;
  if (c.style.color.empty()) c.style.color = palette_color(id);
  ids_[name] = id;
  classes_.push_back(std::move(c));
  return id;
}

std::string LineClasses::unused_style() const {
  for (const auto& [name, style] : styles_) {
    if (ids_.count(name)) continue;
    std::string names;
    for (const LineClass& c : classes_)
      names += (names.empty() ? "" : ", ") + c.name;
    return "--style " + name + ": no feature has class '" + name +
           "' (classes: " + (names.empty() ? "none" : names) +
           "; a class is the layer's name, or the --class-field value after --class-map)";
  }
  return "";
}

double LineClasses::max_half_px() const {
  double m = 0;
  for (const LineClass& c : classes_)
    if (!c.style.width_in_m) m = std::max(m, c.style.half_extent());
  return m;
}

double LineClasses::max_half_m() const {
  double m = 0;
  for (const LineClass& c : classes_)
    if (c.style.width_in_m) m = std::max(m, c.style.half_extent());
  return m;
}

std::string LineClasses::json() const {
  std::string out = "[";
  for (size_t i = 0; i < classes_.size(); ++i) {
    const LineClass& c = classes_[i];
    const LineStyle& s = c.style;
    out += (i ? "," : "") + std::string("{\"id\":") + std::to_string(i) + ",\"name\":\"" +
           tileformat::json_escape(c.name) + "\",\"layer\":\"" + tileformat::json_escape(c.layer) +
           "\",\"features\":" + std::to_string(c.features) + ",\"color\":\"" + s.color +
           "\",\"width\":" + number(s.width) + ",\"unit\":\"" + (s.width_in_m ? "m" : "px") +
           "\",\"casing_color\":\"" + s.casing_color +
           "\",\"casing_width\":" + number(s.casing_width) + ",\"dash\":[";
    for (size_t k = 0; k < s.dash.size(); ++k)
      out += (k ? "," : "") + number(s.dash[k]);
    out += "]";
    if (s.opacity < 1) out += ",\"opacity\":" + number(s.opacity);  // absent: opaque
    if (!s.color_by.empty())
      out += ",\"color_by\":\"" + s.color_by + "\",\"ramp\":\"" + tileformat::json_escape(s.ramp) +
             "\"";
    if (!s.pattern.empty())
      out += ",\"pattern\":\"" + s.pattern + "\",\"pattern_spacing\":" + number(s.pattern_spacing);
    out += "}";
  }
  return out + "]";
}

}  // namespace globe
