// Per-tile warping through GDALWarp (see tile_warper.hpp).
#include "tile_warper.hpp"

#include <cpl_string.h>
#include <gdal_utils.h>

#include <cmath>
#include <limits>

#include "errors.hpp"
#include "spatial_ref.hpp"

namespace globe {

TileWarper::TileWarper(const DemPlan& plan, const std::string& resampling) : plan_(plan) {
  GDALDriverH vrt = GDALGetDriverByName("VRT");
  for (const auto& src : plan.sources) {
    opened_.push_back(GdalDataset::open_raster(src.path));
    const GdalDataset& in = opened_.back();
    for (double shift : src.x_shifts) {
      GDALDatasetH copy = GDALCreateCopy(vrt, "", in.get(), FALSE, nullptr, nullptr, nullptr);
      if (!copy)
        throw InputError(src.path + ": cannot wrap the raster (" + gdal_last_error() + ")");
      GdalDataset wrapped(copy, src.path);
      auto gt = src.geotransform;
      gt[0] += shift;
      GDALSetGeoTransform(copy, gt.data());
      SpatialRef crs = SpatialRef::from_wkt(src.crs_wkt, src.path);
      GDALSetSpatialRef(copy, crs.get());
      for (int b = 1; b <= wrapped.bands(); ++b) {
        if (src.nodata) GDALSetRasterNoDataValue(wrapped.band(b), *src.nodata);
      }
      sources_.push_back(std::move(wrapped));
    }
  }
  const int n = plan.steps;
  GDALDriverH mem = GDALGetDriverByName("MEM");
  dest_ = GdalDataset(GDALCreate(mem, "", n, n, 1, GDT_Float64, nullptr), "tile");
  SpatialRef target = SpatialRef::from_user_input(plan.tiling.crs, "tiling CRS");
  GDALSetSpatialRef(dest_.get(), target.get());
  GDALSetRasterNoDataValue(dest_.band(1), std::numeric_limits<double>::quiet_NaN());

  CPLStringList args;
  args.AddString("-r");
  args.AddString(resampling.c_str());
  args.AddString("-dstnodata");
  args.AddString("nan");
  args.AddString("-wm");
  args.AddString("64");
  options_ = GDALWarpAppOptionsNew(args.List(), nullptr);
  if (!options_) throw std::runtime_error("cannot create GDAL warp options: " + gdal_last_error());
}

TileWarper::~TileWarper() {
  if (options_) GDALWarpAppOptionsFree(static_cast<GDALWarpAppOptions*>(options_));
}

void TileWarper::warp(tileformat::TileId id, std::vector<double>& heights) {
  const int n = plan_.steps;
  const double sp = plan_.tiling.sample_spacing(id.z, plan_.steps);
  const tileformat::Bounds b = plan_.tiling.tile_bounds(id);
  // Pixel centres on the samples: the first centre is the tile's corner.
  double gt[6] = {b.min_x - sp / 2, sp, 0, b.max_y + sp / 2, 0, -sp};
  if (plan_.tiling.scheme == "webmercator") {
    // Warp in a Mercator centred on the tile: identical coordinates up to a
    // shift in x, but the window never touches the +-180 degree wrap, where
    // GDAL's source window computation breaks for tiles at the antimeridian.
    const double centre_x = (b.min_x + b.max_x) / 2;
    const double centre_lon = centre_x / tileformat::kWebMercatorHalf * 180.0;
    const SpatialRef centred = SpatialRef::from_user_input(
        "+proj=merc +a=6378137 +b=6378137 +lat_ts=0 +lon_0=" +
            std::string(CPLSPrintf("%.17g", centre_lon)) +
            " +x_0=0 +y_0=0 +k=1 +units=m +nadgrids=@null +over +wktext +no_defs",
        "tile CRS");
    gt[0] -= centre_lon / 180.0 * tileformat::kWebMercatorHalf;
    GDALSetSpatialRef(dest_.get(), centred.get());
  }
  GDALSetGeoTransform(dest_.get(), gt);
  // Initialised once here, not by GDAL per source (INIT_DEST would let a later
  // source's window wipe what an earlier source wrote: mosaics, +-360 copies).
  if (GDALFillRaster(dest_.band(1), std::numeric_limits<double>::quiet_NaN(), 0) != CE_None)
    throw std::runtime_error("cannot initialise the tile buffer: " + gdal_last_error());
  std::vector<GDALDatasetH> srcs;
  for (auto& s : sources_)
    srcs.push_back(s.get());
  int usage_error = 0;
  CPLErrorReset();
  GDALDatasetH out = GDALWarp(nullptr, dest_.get(), static_cast<int>(srcs.size()), srcs.data(),
                              static_cast<GDALWarpAppOptions*>(options_), &usage_error);
  if (!out || CPLGetLastErrorType() == CE_Failure)
    throw InputError(plan_.sources[0].path +
                     (plan_.sources.size() > 1 ? " (or another input)" : "") +
                     ": reading data for tile " + id.str() + " failed (" + gdal_last_error() +
                     "); the file may be truncated or corrupt");
  heights.resize(static_cast<size_t>(n) * n);
  if (GDALRasterIO(dest_.band(1), GF_Read, 0, 0, n, n, heights.data(), n, n, GDT_Float64, 0, 0) !=
      CE_None)
    throw InputError("tile " + id.str() + ": reading the warped samples failed (" +
                     gdal_last_error() + ")");
}

}  // namespace globe
