// Settings of `globe-tiler imagery`, filled by the command-line parser and
// read by the planner and builder (nothing here touches GDAL).
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "kit/build_options.hpp"
#include "tileformat/image_tile.hpp"

namespace globe {

struct ImageSettings : BuildOptions {
  std::string like;     // adopt this package's tiling
  int tile_size = 256;  // 256 or 512 pixels
  tileformat::ImageFormat format = tileformat::ImageFormat::kPng;
  int quality = 85;
  int png_level = 1;
  std::vector<int> bands;  // source bands: 1 or 3 colour, optionally + alpha
  std::optional<double> nodata;
  std::optional<std::pair<double, double>> scale;  // source range mapped to 0..255
  std::string resampling = "bilinear";
  double transform_error = 0.125;  // pixels, as gdalwarp -et
};

}  // namespace globe
