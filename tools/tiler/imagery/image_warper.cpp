// Image tiles from the imagery mosaic (see image_warper.hpp).
#include "imagery/image_warper.hpp"

#include <cstdio>

#include "geo/spatial_ref.hpp"
#include "runtime/errors.hpp"

namespace globe {
namespace {

// Band selection, palette expansion and 8-bit scaling, as gdal_translate -of VRT.
GdalDataset select_bands(const GdalDataset& in, const ImageSource& src, const ImagePlan& plan) {
  std::vector<std::string> args;
  for (int b : src.colour_bands)
    args.insert(args.end(), {"-b", std::to_string(b)});
  if (src.expand_palette)
    args.insert(args.end(), {"-expand", src.has_alpha_palette ? "rgba" : "rgb"});
  if (src.alpha_band) args.insert(args.end(), {"-b", std::to_string(src.alpha_band)});
  if (plan.scale) {
    args.insert(args.end(), {"-ot", "Byte"});
    char lo[32], hi[32];
    std::snprintf(lo, sizeof lo, "%.17g", plan.scale->first);
    std::snprintf(hi, sizeof hi, "%.17g", plan.scale->second);
    for (size_t i = 1; i <= src.colour_bands.size(); ++i)
      args.insert(args.end(), {"-scale_" + std::to_string(i), lo, hi, "0", "255"});
  }
  GdalDataset wrapped = in.translate_to_vrt(args);
  if (src.alpha_band || src.has_alpha_palette) wrapped.set_colour(wrapped.bands(), GCI_AlphaBand);
  return wrapped;
}

}  // namespace

ImageWarper::ImageWarper(const ImagePlan& plan, const ImageSettings& s)
    : plan_(plan), size_(s.tile_size) {
  std::vector<GdalDataset> sources;
  for (const auto& src : plan.sources) {
    opened_.push_back(GdalDataset::open_raster(src.path));
    const GDALDatasetH in = opened_.back().get();
    for (double shift : warp_shifts(src)) {
      // Inner wrapper: georeferencing and nodata (never written back to the file).
      GdalDataset inner = georeferenced_copy(in, src, shift, s.nodata, src.colour_bands);
      sources.push_back(select_bands(inner, src, plan));
      opened_.push_back(std::move(inner));
    }
  }
  WarpSpec spec;
  spec.target_crs = plan.tiling.crs;
  spec.resampling = s.resampling;
  spec.bands = plan.colour + 1;
  spec.alpha = true;
  spec.type = GDT_Byte;
  spec.max_width = spec.max_height = size_ * kMaxGroup;
  spec.tolerance_px = s.transform_error;
  warper_ = std::make_unique<RasterWarper>(
      std::move(sources), std::move(spec),
      plan.sources[0].path + (plan.sources.size() > 1 ? " (or another input)" : ""));
}

ImageWarper::~ImageWarper() {
  warper_.reset();
  while (!opened_.empty())
    opened_.pop_back();
}

void ImageWarper::warp(tileformat::TileId first, int cols, int rows, std::vector<uint8_t>& planes) {
  if (cols < 1 || rows < 1 || cols > kMaxGroup || rows > kMaxGroup)
    throw std::invalid_argument("ImageWarper: group of " + std::to_string(cols) + " x " +
                                std::to_string(rows) + " tiles");
  const int w = size_ * cols, h = size_ * rows;
  const double px = plan_.tiling.sample_spacing(first.z, size_);
  const tileformat::Bounds b = plan_.tiling.tile_bounds(first);
  const std::array<double, 6> gt = {b.min_x, px, 0, b.max_y, 0, -px};
  planes.assign(size_t(plan_.colour + 1) * w * h, 0);  // transparent background
  warper_->warp(gt, w, h, "tile " + first.str(), planes.data());
}

}  // namespace globe
