// Warps the imagery mosaic onto image tiles' pixels (one ImageWarper per
// worker thread). Each source is wrapped in VRTs that carry its resolved CRS,
// --nodata, longitude shift, band selection, palette expansion and scaling to
// 8 bits, with the alpha band (if any) last; the warping is RasterWarper's,
// which adds coverage as the alpha of every tile pixel.
#pragma once

#include <memory>
#include <vector>

#include "imagery/image_plan.hpp"
#include "raster/raster_warper.hpp"
#include "tileformat/tile_id.hpp"

namespace globe {

class ImageWarper {
 public:
  ImageWarper(const ImagePlan& plan, const ImageSettings& settings);
  ~ImageWarper();  // closes wrappers before what they wrap

  // The pixels of a block of cols x rows tiles whose north-west tile is
  // `first`: plan.colour + 1 planes (alpha last) of (cols * size) x
  // (rows * size) bytes. Throws InputError on read failures.
  void warp(tileformat::TileId first, int cols, int rows, std::vector<uint8_t>& planes);
  static constexpr int kMaxGroup = 4;

 private:
  const ImagePlan& plan_;
  const int size_;
  std::vector<GdalDataset> opened_;  // inputs and inner wrappers; outlive the outer ones
  std::unique_ptr<RasterWarper> warper_;
};

}  // namespace globe
