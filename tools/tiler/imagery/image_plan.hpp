// Planning an imagery build: opens every input once to resolve its CRS,
// colour bands, alpha source and value range, and derives the tiling, the
// zoom range and the areas that hold data (raster_footprint). Throws
// InputError or UsageError with the file name and what to do.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "imagery/image_settings.hpp"
#include "raster/raster_footprint.hpp"

namespace globe {

struct ImageSource : RasterSource {
  std::vector<int> colour_bands;   // source band numbers (1 or 3 of them)
  int alpha_band = 0;              // source alpha band, 0 if none
  bool expand_palette = false;     // paletted: colours come from the colour table
  bool has_alpha_palette = false;  // the palette has transparent entries
};

struct ImagePlan : Footprint {  // tiling, data areas, resolution, zooms
  std::vector<ImageSource> sources;
  int colour = 3;                                  // 1 gray or 3 RGB
  std::optional<std::pair<double, double>> scale;  // non-Byte inputs: range mapped to 0..255
  bool scale_derived = false;                      // from the data, not --scale
};

ImagePlan plan_imagery(const ImageSettings& settings);

}  // namespace globe
