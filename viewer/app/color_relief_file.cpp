// gdaldem color-relief file reader (see color_relief_file.hpp).
#include "app/color_relief_file.hpp"

#include <cctype>
#include <charconv>
#include <fstream>
#include <utility>
#include <vector>

#include "runtime/errors.hpp"

namespace globe::viewer {
namespace {

// The colour names gdaldem accepts.
std::optional<Rgba> named_color(std::string name) {
  for (char& c : name)
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  static const std::pair<const char*, Rgba> kNames[] = {
      {"white", {255, 255, 255, 255}}, {"black", {0, 0, 0, 255}},
      {"red", {255, 0, 0, 255}},       {"green", {0, 255, 0, 255}},
      {"blue", {0, 0, 255, 255}},      {"yellow", {255, 255, 0, 255}},
      {"magenta", {255, 0, 255, 255}}, {"fuchsia", {255, 0, 255, 255}},
      {"cyan", {0, 255, 255, 255}},    {"aqua", {0, 255, 255, 255}},
      {"grey", {190, 190, 190, 255}},  {"gray", {190, 190, 190, 255}},
      {"orange", {255, 165, 0, 255}},  {"brown", {165, 42, 42, 255}},
      {"purple", {160, 32, 240, 255}}, {"violet", {238, 130, 238, 255}},
      {"indigo", {75, 0, 130, 255}}};
  for (const auto& [n, c] : kNames)
    if (name == n) return c;
  return std::nullopt;
}

std::vector<std::string> split_fields(const std::string& line) {
  std::vector<std::string> out;
  std::string cur;
  for (char c : line) {
    if (c == ' ' || c == '\t' || c == ',' || c == ':' || c == '\r') {
      if (!cur.empty()) out.push_back(std::move(cur));
      cur.clear();
    } else {
      cur += c;
    }
  }
  if (!cur.empty()) out.push_back(std::move(cur));
  return out;
}

bool parse_double(const std::string& s, double& v) {
  const char* end = s.data() + s.size();
  const auto r = std::from_chars(s.data(), end, v);
  return r.ec == std::errc() && r.ptr == end;
}

}  // namespace

ColorReliefFile read_color_relief_file(const std::string& path) {
  std::ifstream in(path);
  if (!in)
    throw InputError(path + ": cannot read the colour file (a gdaldem color-relief text file)");
  ColorReliefFile f;
  f.ramp.source = path;
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    const auto hash = line.find('#');
    if (hash != std::string::npos) line.resize(hash);
    const std::vector<std::string> w = split_fields(line);
    if (w.empty()) continue;
    const auto fail = [&](const std::string& what) {
      throw InputError(path + ":" + std::to_string(n) + ": " + what +
                       " (expected 'VALUE R G B [A]', 'VALUE NAME', a percentage like '50%' "
                       "or 'nv' as VALUE; gdaldem color-relief format)");
    };
    Rgba c{0, 0, 0, 255};
    if (w.size() == 2) {
      const auto named = named_color(w[1]);
      if (!named) fail("unknown colour name '" + w[1] + "'");
      c = *named;
    } else if (w.size() == 4 || w.size() == 5) {
      for (size_t b = 1; b < w.size(); ++b) {
        double v = 0;
        if (!parse_double(w[b], v) || v < 0 || v > 255 || v != static_cast<int>(v))
          fail("colour component '" + w[b] + "' is not an integer 0..255");
        c[b - 1] = static_cast<uint8_t>(v);
      }
    } else {
      fail("expected 2, 4 or 5 fields, found " + std::to_string(w.size()));
    }
    if (w[0] == "nv") {
      f.nodata = c;
      continue;
    }
    RampStop s;
    s.color = c;
    std::string v = w[0];
    if (v.back() == '%') {
      s.percent = true;
      v.pop_back();
    }
    if (!parse_double(v, s.value)) fail("value '" + w[0] + "' is not a number");
    f.ramp.stops.push_back(s);
  }
  if (f.ramp.stops.empty())
    throw InputError(path +
                     ": the colour file has no colour stops (gdaldem color-relief format: "
                     "one 'VALUE R G B' per line)");
  return f;
}

}  // namespace globe::viewer
