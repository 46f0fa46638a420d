// The session's elevation ramp (see elevation_ramp.hpp).
#include "app/elevation_ramp.hpp"

#include <cmath>
#include <cstdio>
#include <system_error>
#include <tuple>

namespace globe::viewer {

ElevationRamp::ElevationRamp(const ShadingSettings& settings) : settings_(settings) {
  if (!is_builtin_ramp(settings_.colormap)) {
    file_ = read_color_relief_file(settings_.colormap);
    std::error_code ec;
    file_time_ = std::filesystem::last_write_time(settings_.colormap, ec);
  }
}

void ElevationRamp::add_samples(const LoadedBlock& block) {
  if (finished_) return;
  for (size_t i = 0; i < block.heights.size(); ++i)
    if (block.mask[i]) samples_.push_back(block.heights[i]);
}

void ElevationRamp::finish() {
  if (settings_.height_range) {
    std::tie(lo_, hi_) = *settings_.height_range;
  } else {
    std::tie(lo_, hi_) = percentile_range(samples_, settings_.height_percentile);
  }
  if (!(hi_ > lo_)) hi_ = lo_ + 1;
  samples_ = {};
  finished_ = true;
}

RampTable ElevationRamp::table(Shading mode, float flow_top) const {
  const ShadingMode& m = shading_mode(mode);
  double lo = lo_, hi = hi_;
  if (m.ramp == RampDomain::kFixed) lo = m.lo, hi = m.hi;
  if (m.ramp == RampDomain::kFlowLog2) lo = flow_top - 16.0, hi = flow_top;
  ColorRamp ramp = file_ ? file_->ramp : builtin_ramp(settings_.colormap, lo, hi);
  if (file_ && m.ramp == RampDomain::kFlowLog2)  // the file's areas in m^2, the table in log2
    for (RampStop& stop : ramp.stops)
      if (!stop.percent) stop.value = stop.value > 0 ? std::log2(stop.value) : lo;
  RampTable t = tabulate(ramp, lo, hi);
  // Shift and stretch about the middle of the domain: the table is linear
  // in the value, so moving its ends moves every stop alike.
  const double c = (lo + hi) / 2;
  t.lo = c + (t.lo - c) * stretch_ + shift_ * (hi - lo);
  t.hi = c + (t.hi - c) * stretch_ + shift_ * (hi - lo);
  return t;
}

bool ElevationRamp::reload(Reload when) {
  if (!file_) return false;
  std::error_code ec;
  const auto t = std::filesystem::last_write_time(settings_.colormap, ec);
  if (when == Reload::kIfChanged && (ec || t == file_time_)) return false;
  file_time_ = t;
  try {
    file_ = read_color_relief_file(settings_.colormap);
    std::fprintf(stderr, "globe-view: colour ramp reloaded from %s\n", settings_.colormap.c_str());
    return true;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "globe-view: %s; keeping the previous colour ramp\n", e.what());
    return false;
  }
}

}  // namespace globe::viewer
