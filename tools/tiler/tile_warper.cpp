// Per-tile warping through GDAL's warp operation (see tile_warper.hpp).
#include "tile_warper.hpp"

#include <cpl_string.h>
#include <gdal_alg.h>
#include <gdalwarper.h>

#include <cmath>
#include <limits>

#include "errors.hpp"
#include "spatial_ref.hpp"

namespace globe {
namespace {

GDALResampleAlg resample_alg(const std::string& name) {
  static const std::pair<const char*, GDALResampleAlg> kAlgs[] = {{"near", GRA_NearestNeighbour},
                                                                  {"bilinear", GRA_Bilinear},
                                                                  {"cubic", GRA_Cubic},
                                                                  {"cubicspline", GRA_CubicSpline},
                                                                  {"lanczos", GRA_Lanczos},
                                                                  {"average", GRA_Average},
                                                                  {"min", GRA_Min},
                                                                  {"max", GRA_Max},
                                                                  {"med", GRA_Med},
                                                                  {"mode", GRA_Mode}};
  for (const auto& [n, alg] : kAlgs)
    if (name == n) return alg;
  throw UsageError("--resampling: unknown method '" + name + "'");
}

}  // namespace

struct TileWarper::Operation {
  void* transformer = nullptr;  // GenImgProj, owned by `approx`
  void* approx = nullptr;
  GDALWarpOptions* options = nullptr;
  GDALWarpOperationH operation = nullptr;
  ~Operation() {
    if (operation) GDALDestroyWarpOperation(operation);
    if (options) {
      options->pTransformerArg = nullptr;
      GDALDestroyWarpOptions(options);
    }
    if (approx) GDALDestroyApproxTransformer(approx);
  }
};

TileWarper::TileWarper(const DemPlan& plan, const std::string& resampling)
    : plan_(plan), resampling_(resampling) {
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
      if (src.nodata) GDALSetRasterNoDataValue(wrapped.band(1), *src.nodata);
      sources_.push_back(std::move(wrapped));
    }
  }
  const int n = plan.steps * kMaxGroup;
  GDALDriverH mem = GDALGetDriverByName("MEM");
  dest_ = GdalDataset(GDALCreate(mem, "", n, n, 1, GDT_Float64, nullptr), "tile");
  SpatialRef target = SpatialRef::from_user_input(plan.tiling.crs, "tiling CRS");
  GDALSetSpatialRef(dest_.get(), target.get());
  GDALSetRasterNoDataValue(dest_.band(1), std::numeric_limits<double>::quiet_NaN());
  // GDAL derives transformer settings (e.g. longitude wrapping) from the
  // destination extent at creation: give it a real tile of the finest zoom.
  const auto& area = plan.data_areas.front();
  const auto range = plan.tiling.tiles_covering(area, plan.max_zoom);
  const auto b = plan.tiling.tile_bounds(
      {plan.max_zoom, (range.min_x + range.max_x) / 2, (range.min_y + range.max_y) / 2});
  const double sp = plan.tiling.sample_spacing(plan.max_zoom, plan.steps);
  double gt[6] = {b.min_x - sp / 2, sp, 0, b.max_y + sp / 2, 0, -sp};
  GDALSetGeoTransform(dest_.get(), gt);
  operations_ = make_operations();
}

TileWarper::~TileWarper() = default;

// One warp operation per source, for the destination's current CRS.
std::vector<std::unique_ptr<TileWarper::Operation>> TileWarper::make_operations() {
  std::vector<std::unique_ptr<Operation>> ops;
  const GDALResampleAlg alg = resample_alg(resampling_);
  for (auto& src : sources_) {
    auto op = std::make_unique<Operation>();
    CPLErrorReset();
    op->transformer = GDALCreateGenImgProjTransformer2(src.get(), dest_.get(), nullptr);
    if (!op->transformer)
      throw InputError(src.name() + ": no transformation to the tiling CRS (" + gdal_last_error() +
                       ")");
    // The same error threshold as gdalwarp's default (0.125 pixel).
    op->approx = GDALCreateApproxTransformer(GDALGenImgProjTransform, op->transformer, 0.125);
    GDALApproxTransformerOwnsSubtransformer(op->approx, TRUE);
    GDALWarpOptions* o = GDALCreateWarpOptions();
    op->options = o;
    o->hSrcDS = src.get();
    o->hDstDS = dest_.get();
    o->nBandCount = 1;
    o->panSrcBands = static_cast<int*>(CPLMalloc(sizeof(int)));
    o->panDstBands = static_cast<int*>(CPLMalloc(sizeof(int)));
    o->panSrcBands[0] = o->panDstBands[0] = 1;
    o->eResampleAlg = alg;
    o->eWorkingDataType = GDT_Float64;
    o->dfWarpMemoryLimit = 64.0 * 1024 * 1024;
    o->pfnTransformer = GDALApproxTransform;
    o->pTransformerArg = op->approx;
    int has_nodata = 0;
    const double src_nodata = GDALGetRasterNoDataValue(src.band(1), &has_nodata);
    if (has_nodata) {
      o->padfSrcNoDataReal = static_cast<double*>(CPLMalloc(sizeof(double)));
      o->padfSrcNoDataReal[0] = src_nodata;
    }
    o->padfDstNoDataReal = static_cast<double*>(CPLMalloc(sizeof(double)));
    o->padfDstNoDataReal[0] = std::numeric_limits<double>::quiet_NaN();
    op->operation = GDALCreateWarpOperation(o);
    if (!op->operation)
      throw InputError(src.name() + ": cannot set up warping (" + gdal_last_error() + ")");
    ops.push_back(std::move(op));
  }
  return ops;
}

void TileWarper::warp(tileformat::TileId id, int cols, int rows, std::vector<double>& heights) {
  if (cols < 1 || rows < 1 || cols > kMaxGroup || rows > kMaxGroup)
    throw std::invalid_argument("TileWarper: group of " + std::to_string(cols) + " x " +
                                std::to_string(rows) + " tiles");
  const int w = plan_.steps * cols, h = plan_.steps * rows;
  const double sp = plan_.tiling.sample_spacing(id.z, plan_.steps);
  const tileformat::Bounds first = plan_.tiling.tile_bounds(id);
  const tileformat::Bounds b{first.min_x, first.max_y - rows * first.height(),
                             first.min_x + cols * first.width(), first.max_y};
  // Pixel centres on the samples: the first centre is the tile's corner.
  double gt[6] = {b.min_x - sp / 2, sp, 0, b.max_y + sp / 2, 0, -sp};
  // Initialised once here, not by GDAL per source (INIT_DEST would let a later
  // source's window wipe what an earlier source wrote: mosaics, +-360 copies).
  heights.assign(static_cast<size_t>(w) * h, std::numeric_limits<double>::quiet_NaN());
  if (GDALRasterIO(dest_.band(1), GF_Write, 0, 0, w, h, heights.data(), w, h, GDT_Float64, 0, 0) !=
      CE_None)
    throw std::runtime_error("cannot initialise the tile buffer: " + gdal_last_error());

  std::vector<std::unique_ptr<Operation>> centred;
  const bool at_antimeridian = plan_.tiling.scheme == "webmercator" &&
                               (id.x == 0 || id.x + cols >= plan_.tiling.tiles_x(id.z));
  if (at_antimeridian) {
    // Warp in a Mercator centred on the tile (with +over, longitudes continue
    // past +-180): the same projection up to a shift in x, but the window
    // stays away from the wrap, where GDAL's source window computation breaks.
    const double centre_lon = (b.min_x + b.max_x) / 2 / tileformat::kWebMercatorHalf * 180.0;
    const SpatialRef crs = SpatialRef::from_user_input(
        "+proj=merc +a=6378137 +b=6378137 +lat_ts=0 +lon_0=" +
            std::string(CPLSPrintf("%.17g", centre_lon)) +
            " +x_0=0 +y_0=0 +k=1 +units=m +nadgrids=@null +over +wktext +no_defs",
        "tile CRS");
    gt[0] -= centre_lon / 180.0 * tileformat::kWebMercatorHalf;
    GDALSetSpatialRef(dest_.get(), crs.get());
    GDALSetGeoTransform(dest_.get(), gt);
    centred = make_operations();
    const SpatialRef target = SpatialRef::from_user_input(plan_.tiling.crs, "tiling CRS");
    GDALSetSpatialRef(dest_.get(), target.get());
  }
  auto& ops = at_antimeridian ? centred : operations_;
  CPLErrorReset();
  for (auto& op : ops) {
    GDALSetGenImgProjTransformerDstGeoTransform(op->transformer, gt);
    if (GDALChunkAndWarpImage(op->operation, 0, 0, w, h) != CE_None ||
        CPLGetLastErrorType() == CE_Failure)
      throw InputError(plan_.sources[0].path +
                       (plan_.sources.size() > 1 ? " (or another input)" : "") +
                       ": reading data for tile " + id.str() + " failed (" + gdal_last_error() +
                       "); the file may be truncated or corrupt");
  }
  heights.resize(static_cast<size_t>(w) * h);
  if (GDALRasterIO(dest_.band(1), GF_Read, 0, 0, w, h, heights.data(), w, h, GDT_Float64, 0, 0) !=
      CE_None)
    throw InputError("tile " + id.str() + ": reading the warped samples failed (" +
                     gdal_last_error() + ")");
}

}  // namespace globe
