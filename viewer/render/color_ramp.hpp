// Transfer functions for height-like values: a list of colour stops (as in
// gdaldem color-relief files: absolute values or percentages of the data
// range) resolved into a lookup table the terrain shader samples. Pure CPU
// code, no GL.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace globe::viewer {

using Rgba = std::array<uint8_t, 4>;

struct RampStop {
  double value = 0;      // metres, or percent of the data range when `percent`
  bool percent = false;  // gdaldem's "50%": min + 0.5 * (max - min)
  Rgba color{0, 0, 0, 255};
};

// Stops in ascending order of their resolved values; colours between two
// stops blend linearly, values outside take the first or last colour
// (gdaldem color-relief's default interpolation).
struct ColorRamp {
  std::string source;  // file path or built-in name, for messages
  std::vector<RampStop> stops;
};

// The table the shader reads: kEntries colours evenly spanning lo..hi,
// entry i at lo + i * (hi - lo) / (kEntries - 1).
struct RampTable {
  static constexpr int kEntries = 4096;
  double lo = 0, hi = 1;
  std::vector<uint8_t> rgba;    // kEntries * 4
  Rgba at(double value) const;  // nearest entry; for tests and the legend
};

// Names of the built-in ramps, for --help and errors.
const std::vector<std::string>& builtin_ramp_names();
bool is_builtin_ramp(const std::string& name);

// A built-in ramp for data from lo to hi metres. "hypsometric": land from
// green lowlands over tan and brown to white peaks across max(lo, 0)..hi,
// and, where lo < 0, bathymetry from light blue at the coast to deep blue at
// lo, so sea and land differ at any range; "gray": black to white.
ColorRamp builtin_ramp(const std::string& name, double lo, double hi);

// Resolves percentages against data_min..data_max and tabulates the ramp.
// Throws std::invalid_argument for a ramp without stops.
RampTable tabulate(const ColorRamp& ramp, double data_min, double data_max);

// The p-th and (100 - p)-th percentiles of `values` (0 <= p < 50; p = 0
// gives min and max). Reorders `values`. {0, 0} when empty.
std::pair<double, double> percentile_range(std::vector<float>& values, double p);

}  // namespace globe::viewer
