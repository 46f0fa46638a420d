// Chart styles (see chart_style.hpp).
#include "app/chart_style.hpp"

#include <fstream>
#include <sstream>

#include "runtime/errors.hpp"
#include "runtime/line_style.hpp"
#include "tileformat/json.hpp"

namespace globe::viewer {

using tileformat::JsonValue;

ChartStyle read_chart_style(const std::vector<std::string>& fields,
                            const std::optional<std::string>& path) {
  ChartStyle s;
  for (size_t i = 0; i < fields.size(); ++i)
    s.colors.push_back(palette_color(i));
  if (!path) return s;
  std::ifstream in(*path);
  if (!in) throw InputError(*path + ": cannot read the chart style file");
  std::stringstream text;
  text << in.rdbuf();
  JsonValue root;
  try {
    root = JsonValue::parse(text.str());
  } catch (const tileformat::JsonError& e) {
    throw InputError(*path + ": not valid JSON (" + e.what() + ")");
  }
  if (!root.is_object()) throw InputError(*path + ": expected a JSON object of chart settings");
  auto number = [&](const std::string& key, const JsonValue& v, double lo, double hi) {
    if (!v.is_number() || !(v.number() >= lo && v.number() <= hi))
      throw InputError(*path + ": \"" + key + "\" must be a number within " + std::to_string(lo) +
                       ".." + std::to_string(hi));
    return v.number();
  };
  auto color = [&](const std::string& key, const JsonValue& v) {
    if (!v.is_string() || !is_hex_color(v.string()))
      throw InputError(*path + ": \"" + key + "\" must be a colour \"#rrggbb\"");
    return v.string();
  };
  for (const auto& [key, v] : root.members()) {
    if (key == "colors") {
      if (!v.is_object()) throw InputError(*path + ": \"colors\" must map field names to colours");
      for (const auto& [field, c] : v.members()) {
        size_t i = 0;
        while (i < fields.size() && fields[i] != field)
          ++i;
        if (i == fields.size()) {
          std::string names;
          for (const std::string& f : fields)
            names += (names.empty() ? "" : ", ") + f;
          throw InputError(*path + ": \"colors\" names field '" + field +
                           "', which the package does not have (its fields: " + names + ")");
        }
        s.colors[i] = color("colors." + field, c);
      }
    } else if (key == "min_px") {
      s.min_px = number(key, v, 1, 1024);
    } else if (key == "max_px") {
      s.max_px = number(key, v, 1, 1024);
    } else if (key == "outline") {
      s.outline = color(key, v);
    } else if (key == "outline_px") {
      s.outline_px = number(key, v, 0, 16);
    } else if (key == "opacity") {
      s.opacity = number(key, v, 0, 1);
    } else if (key == "legend") {
      if (!v.is_bool()) throw InputError(*path + ": \"legend\" must be true or false");
      s.legend = v.boolean();
    } else if (key == "column_px") {
      s.column_px = number(key, v, 1, 4096);
    } else {
      throw InputError(*path + ": unknown key \"" + key +
                       "\" (colors, min_px, max_px, outline, outline_px, opacity, legend, "
                       "column_px)");
    }
  }
  if (s.min_px > s.max_px) throw InputError(*path + ": \"min_px\" is above \"max_px\"");
  return s;
}

}  // namespace globe::viewer
