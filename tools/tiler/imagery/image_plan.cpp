// Imagery build planning (see image_plan.hpp, docs/imagery.md "Planning").
#include "imagery/image_plan.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "geo/gdal_dataset.hpp"
#include "raster/raster_warper.hpp"
#include "runtime/errors.hpp"

namespace globe {
namespace {

std::string list(const std::vector<int>& v) {
  std::string s;
  for (int b : v)
    s += (s.empty() ? "" : ",") + std::to_string(b);
  return s;
}

void check_settings(const ImageSettings& s) {
  check_tiling_options(s, s.like);
  if (s.tile_size != 256 && s.tile_size != 512)
    throw UsageError("--tile-size: " + std::to_string(s.tile_size) + " is not 256 or 512");
  if (!is_resampling(s.resampling))
    throw UsageError("--resampling: '" + s.resampling + "' is not one of " + kResamplingNames);
  if (s.quality < 1 || s.quality > 100) throw UsageError("--quality must be 1..100");
  if (!(s.transform_error >= 0)) throw UsageError("--transform-error must be >= 0");
  if (!s.bands.empty() && (s.bands.size() > 4))
    throw UsageError("--bands " + list(s.bands) +
                     ": give 1 (gray) or 3 (RGB) bands, optionally followed by an alpha band");
  if (s.scale && !(s.scale->second > s.scale->first))
    throw UsageError("--scale: MAX must be larger than MIN");
}

// Which source bands give colour and alpha.
void choose_bands(const GdalDataset& ds, const ImageSettings& s, ImageSource& src) {
  const int n = ds.bands();
  if (n < 1) throw InputError(src.path + ": has no raster bands");
  if (!s.bands.empty()) {
    for (int b : s.bands)
      if (b < 1 || b > n)
        throw UsageError("--bands " + list(s.bands) + ": " + src.path + " has " +
                         std::to_string(n) + " band" + (n == 1 ? "" : "s"));
    const size_t k = s.bands.size();
    const size_t colour = k >= 3 ? 3 : 1;
    src.colour_bands.assign(s.bands.begin(), s.bands.begin() + colour);
    if (k == 2 || k == 4) src.alpha_band = s.bands.back();
    return;
  }
  if (const std::optional<bool> translucent = ds.palette_translucent(1)) {
    src.expand_palette = true;
    src.colour_bands = {1};
    src.has_alpha_palette = *translucent;
    return;
  }
  std::vector<int> colour;
  for (int b = 1; b <= n; ++b) {
    if (ds.colour(b) == GCI_AlphaBand)
      src.alpha_band = b;
    else
      colour.push_back(b);
  }
  if (colour.empty()) throw InputError(src.path + ": has only an alpha band");
  src.colour_bands.assign(colour.begin(), colour.begin() + (colour.size() >= 3 ? 3 : 1));
}

}  // namespace

ImagePlan plan_imagery(const ImageSettings& s) {
  check_settings(s);
  gdal_init();
  ImagePlan plan;
  std::optional<SpatialRef> s_srs;
  if (!s.s_srs.empty()) s_srs = SpatialRef::from_user_input(s.s_srs, "--s_srs");

  std::vector<RasterSource> rasters;
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  bool needs_scale = false;
  for (const auto& path : s.inputs) {
    GdalDataset ds = GdalDataset::open_raster(path);
    rasters.push_back(describe_raster(ds, path, s_srs));
    ImageSource src;
    src.path = path;
    choose_bands(ds, s, src);
    const int colour = src.expand_palette ? 3 : static_cast<int>(src.colour_bands.size());
    if (plan.sources.empty()) {
      plan.colour = colour;
    } else if (colour != plan.colour) {
      throw InputError(path + " gives " + std::to_string(colour) + " colour band(s), " +
                       plan.sources[0].path + " " + std::to_string(plan.colour) +
                       "; pick matching bands with --bands");
    }
    for (int b : src.colour_bands) {
      if (ds.data_type(b) == GDT_Byte || src.expand_palette) continue;
      needs_scale = true;
      if (s.scale) continue;
      if (s.nodata) ds.set_nodata(b, *s.nodata);  // this handle only
      const auto mm = ds.min_max(b, Scan::kApproximate);
      if (!mm || !std::isfinite((*mm)[0]) || !std::isfinite((*mm)[1]))
        throw InputError(path + ": cannot read band " + std::to_string(b) + " (" +
                         gdal_last_error() + "); the file may be truncated, or hold no valid data");
      lo = std::min(lo, (*mm)[0]);
      hi = std::max(hi, (*mm)[1]);
    }
    plan.sources.push_back(std::move(src));
  }
  if (s.scale) {
    plan.scale = s.scale;
  } else if (needs_scale) {
    plan.scale = std::pair{lo, hi > lo ? hi : lo + 1};
    plan.scale_derived = true;
  }

  static_cast<Footprint&>(plan) = plan_footprint(rasters, s, s.like, TileGrid{s.tile_size, false});
  for (size_t i = 0; i < rasters.size(); ++i)
    static_cast<RasterSource&>(plan.sources[i]) = rasters[i];
  return plan;
}

}  // namespace globe
