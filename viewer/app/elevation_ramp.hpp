// The session's transfer function: which ramp (built-in or a gdaldem
// color-relief file, reloaded when it changes), over which values, and the
// window's shift and stretch of it (the thesis's transfer-function editor).
// Elevation spans the data's own heights (the valid samples of the coarsest
// blocks, clipped to percentiles, unless --height-range); with --colormap the
// other layers take the ramp over their natural domains: slope 0..90
// degrees, sky view 0..1, flow log2 of the upstream area over the 16
// doublings below the largest (a file's values are in m^2 there).
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "app/color_relief_file.hpp"
#include "data/block_cache.hpp"
#include "render/color_ramp.hpp"
#include "render/terrain_renderer.hpp"

namespace globe::viewer {

class ElevationRamp {
 public:
  // Reads the colour file now (throws InputError for a bad one).
  explicit ElevationRamp(const ShadingSettings& settings);

  // Heights of a coarsest-zoom block (valid samples only), before finish().
  void add_samples(const LoadedBlock& block);
  size_t sample_count() const { return samples_.size(); }
  void clear_samples() { samples_.clear(); }
  // Fixes the data range from the samples added (or --height-range).
  void finish();
  bool finished() const { return finished_; }
  std::pair<double, double> data_range() const { return {lo_, hi_}; }

  RampTable table() const { return table(Shading::kElevation, 0); }
  // The table for a shading mode's values; flow_top: log2 of the largest
  // upstream area (m^2) loaded.
  RampTable table(Shading mode, float flow_top) const;

  // Window edits, as fractions of the data range: shift moves the ramp up,
  // stretch > 1 spreads it over more metres. reset() undoes them.
  void shift(double fraction) { shift_ += fraction; }
  void stretch(double factor) { stretch_ *= factor; }
  void reset() { shift_ = 0, stretch_ = 1; }

  enum class Reload { kIfChanged, kAlways };
  // Re-reads a colour file; false when nothing changed. A file that no longer
  // parses is reported on stderr and the previous ramp stays.
  bool reload(Reload when);

 private:
  ShadingSettings settings_;
  std::optional<ColorReliefFile> file_;
  std::filesystem::file_time_type file_time_{};
  std::vector<float> samples_;
  bool finished_ = false;
  double lo_ = 0, hi_ = 1;
  double shift_ = 0, stretch_ = 1;  // shift: a fraction of the domain
};

}  // namespace globe::viewer
