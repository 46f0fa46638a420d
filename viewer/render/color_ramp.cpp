// Colour ramps and their lookup tables (see color_ramp.hpp).
#include "render/color_ramp.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace globe::viewer {
namespace {

struct FractionStop {
  double t;  // 0..1 along the span
  Rgba color;
};

// Land, from the lowest land height (t = 0) to the highest (t = 1).
constexpr FractionStop kLand[] = {{0.00, {58, 122, 63, 255}},   {0.12, {132, 178, 96, 255}},
                                  {0.30, {228, 214, 152, 255}}, {0.55, {176, 132, 86, 255}},
                                  {0.80, {134, 104, 86, 255}},  {1.00, {250, 250, 250, 255}}};
// Sea, from the coast (t = 0) to the deepest point (t = 1).
constexpr FractionStop kSea[] = {
    {0.00, {170, 214, 245, 255}}, {0.25, {96, 160, 214, 255}}, {1.00, {12, 40, 104, 255}}};

}  // namespace

const std::vector<std::string>& builtin_ramp_names() {
  static const std::vector<std::string> names{"hypsometric", "gray"};
  return names;
}

bool is_builtin_ramp(const std::string& name) {
  const auto& n = builtin_ramp_names();
  return std::find(n.begin(), n.end(), name) != n.end();
}

ColorRamp builtin_ramp(const std::string& name, double lo, double hi) {
  ColorRamp r;
  r.source = name;
  if (!(hi > lo)) hi = lo + 1;
  if (name == "gray") {
    r.stops = {{lo, false, {0, 0, 0, 255}}, {hi, false, {255, 255, 255, 255}}};
    return r;
  }
  if (name != "hypsometric")
    throw std::invalid_argument("unknown built-in colour ramp '" + name + "'");
  if (lo < 0) {
    // Deepest first; the coast colour ends just below 0 so the shore is sharp.
    const double coast = std::min(hi, 0.0) - std::max(1e-3, (0 - lo) * 1e-6);
    for (int i = static_cast<int>(std::size(kSea)) - 1; i >= 0; --i)
      r.stops.push_back({coast + kSea[i].t * (lo - coast), false, kSea[i].color});
  }
  if (hi > 0) {
    const double land_lo = std::max(lo, 0.0);
    for (const FractionStop& s : kLand)
      r.stops.push_back({land_lo + s.t * (hi - land_lo), false, s.color});
  }
  return r;
}

Rgba RampTable::at(double value) const {
  const double t = (value - lo) / (hi - lo);
  const int i = std::clamp(static_cast<int>(std::lround(t * (kEntries - 1))), 0, kEntries - 1);
  return {rgba[i * 4], rgba[i * 4 + 1], rgba[i * 4 + 2], rgba[i * 4 + 3]};
}

RampTable tabulate(const ColorRamp& ramp, double data_min, double data_max) {
  if (ramp.stops.empty())
    throw std::invalid_argument(ramp.source + ": the colour ramp has no stops");
  std::vector<std::pair<double, Rgba>> s;
  for (const RampStop& st : ramp.stops)
    s.push_back(
        {st.percent ? data_min + st.value / 100 * (data_max - data_min) : st.value, st.color});
  std::stable_sort(s.begin(), s.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  RampTable t;
  t.lo = s.front().first;
  t.hi = s.back().first;
  if (!(t.hi > t.lo)) t.hi = t.lo + 1;
  t.rgba.resize(RampTable::kEntries * 4);
  size_t k = 0;  // s[k].first <= v < s[k + 1].first
  for (int i = 0; i < RampTable::kEntries; ++i) {
    const double v = t.lo + (t.hi - t.lo) * i / (RampTable::kEntries - 1);
    while (k + 1 < s.size() && s[k + 1].first <= v)
      ++k;
    Rgba c = s[k].second;
    if (k + 1 < s.size() && v >= s[k].first) {
      const double f = (v - s[k].first) / (s[k + 1].first - s[k].first);
      for (int b = 0; b < 4; ++b)
        c[b] = static_cast<uint8_t>(
            std::lround(s[k].second[b] + f * (int(s[k + 1].second[b]) - int(s[k].second[b]))));
    }
    std::copy(c.begin(), c.end(), t.rgba.begin() + i * 4);
  }
  return t;
}

std::pair<double, double> percentile_range(std::vector<float>& values, double p) {
  if (values.empty()) return {0, 0};
  const size_t n = values.size();
  const auto rank = [&](double q) {
    return std::min(n - 1, static_cast<size_t>(std::floor(q / 100 * static_cast<double>(n - 1))));
  };
  const size_t a = rank(p), b = rank(100 - p);
  std::nth_element(values.begin(), values.begin() + a, values.end());
  const double lo = values[a];
  std::nth_element(values.begin(), values.begin() + b, values.end());
  return {lo, values[b]};
}

}  // namespace globe::viewer
