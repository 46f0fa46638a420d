// Windowed warping through GDAL's warp operation (see raster_warper.hpp).
#include "raster_warper.hpp"

#include <cpl_string.h>
#include <gdal_alg.h>
#include <gdalwarper.h>

#include <cmath>
#include <limits>
#include <numeric>

#include "errors.hpp"
#include "spatial_ref.hpp"

namespace globe {
namespace {

constexpr std::pair<const char*, GDALResampleAlg> kAlgs[] = {{"near", GRA_NearestNeighbour},
                                                             {"bilinear", GRA_Bilinear},
                                                             {"cubic", GRA_Cubic},
                                                             {"cubicspline", GRA_CubicSpline},
                                                             {"lanczos", GRA_Lanczos},
                                                             {"average", GRA_Average},
                                                             {"min", GRA_Min},
                                                             {"max", GRA_Max},
                                                             {"med", GRA_Med},
                                                             {"mode", GRA_Mode}};

GDALResampleAlg resample_alg(const std::string& name) {
  for (const auto& [n, alg] : kAlgs)
    if (name == n) return alg;
  throw UsageError("--resampling: '" + name + "' is not one of " + kResamplingNames);
}

int* band_list(int n) {
  int* list = static_cast<int*>(CPLMalloc(sizeof(int) * n));
  std::iota(list, list + n, 1);
  return list;
}

}  // namespace

const char* const kResamplingNames =
    "near, bilinear, cubic, cubicspline, lanczos, average, min, max, med, mode";

bool is_resampling(const std::string& name) {
  for (const auto& [n, alg] : kAlgs)
    if (name == n) return true;
  return false;
}

struct RasterWarper::Operation {
  void* transformer = nullptr;  // GenImgProj, owned by `approx` (or by `options`)
  void* approx = nullptr;
  GDALWarpOptions* options = nullptr;
  GDALWarpOperationH operation = nullptr;
  ~Operation() {
    if (operation) GDALDestroyWarpOperation(operation);
    if (options) {
      options->pTransformerArg = nullptr;
      GDALDestroyWarpOptions(options);
    }
    if (approx)
      GDALDestroyApproxTransformer(approx);
    else if (transformer)
      GDALDestroyGenImgProjTransformer(transformer);
  }
};

RasterWarper::RasterWarper(std::vector<GdalDataset> sources, WarpSpec spec, std::string inputs)
    : sources_(std::move(sources)),
      spec_(std::move(spec)),
      inputs_(std::move(inputs)),
      target_(SpatialRef::from_user_input(spec_.tiling.crs, "tiling CRS")) {
  GDALDriverH mem = GDALGetDriverByName("MEM");
  dest_ = GdalDataset(
      GDALCreate(mem, "", spec_.max_width, spec_.max_height, spec_.bands, spec_.type, nullptr),
      "window");
  if (!dest_.get()) throw std::runtime_error("cannot create the warp buffer: " + gdal_last_error());
  GDALSetSpatialRef(dest_.get(), target_.get());
  if (spec_.alpha) GDALSetRasterColorInterpretation(dest_.band(spec_.bands), GCI_AlphaBand);
  if (spec_.nan_nodata)
    for (int b = 1; b <= spec_.bands; ++b)
      GDALSetRasterNoDataValue(dest_.band(b), std::numeric_limits<double>::quiet_NaN());
  GDALSetGeoTransform(dest_.get(), spec_.initial_gt.data());
  make_operations();  // fails early, naming the input, if there is no transformation
}

RasterWarper::~RasterWarper() = default;

// One warp operation per source, for the destination's current CRS.
std::vector<std::unique_ptr<RasterWarper::Operation>> RasterWarper::make_operations() {
  std::vector<std::unique_ptr<Operation>> ops;
  const GDALResampleAlg alg = resample_alg(spec_.resampling);
  const int colour_bands = spec_.bands - (spec_.alpha ? 1 : 0);
  for (auto& src : sources_) {
    auto op = std::make_unique<Operation>();
    CPLErrorReset();
    op->transformer = GDALCreateGenImgProjTransformer2(src.get(), dest_.get(), nullptr);
    if (!op->transformer)
      throw InputError(src.name() + ": no transformation to the tiling CRS (" + gdal_last_error() +
                       ")");
    GDALWarpOptions* o = GDALCreateWarpOptions();
    op->options = o;
    if (spec_.error_threshold > 0) {
      op->approx = GDALCreateApproxTransformer(GDALGenImgProjTransform, op->transformer,
                                               spec_.error_threshold);
      GDALApproxTransformerOwnsSubtransformer(op->approx, TRUE);
      o->pfnTransformer = GDALApproxTransform;
      o->pTransformerArg = op->approx;
    } else {
      o->pfnTransformer = GDALGenImgProjTransform;
      o->pTransformerArg = op->transformer;
    }
    o->hSrcDS = src.get();
    o->hDstDS = dest_.get();
    o->nBandCount = colour_bands;
    o->panSrcBands = band_list(colour_bands);
    o->panDstBands = band_list(colour_bands);
    const int src_bands = src.bands();
    if (spec_.alpha) {
      o->nDstAlphaBand = spec_.bands;
      if (src_bands == colour_bands + 1 &&
          GDALGetRasterColorInterpretation(src.band(src_bands)) == GCI_AlphaBand)
        o->nSrcAlphaBand = src_bands;
    }
    o->eResampleAlg = alg;
    o->eWorkingDataType = spec_.type;
    o->dfWarpMemoryLimit = 64.0 * 1024 * 1024;
    // Source nodata: a pixel is empty when every band that has a nodata value
    // holds it (PARTIAL; GDAL's default would judge each band on its own).
    bool any_nodata = false;
    std::vector<double> nodata(colour_bands, 0.0);
    for (int b = 0; b < colour_bands; ++b) {
      int has = 0;
      nodata[b] = GDALGetRasterNoDataValue(src.band(b + 1), &has);
      any_nodata = any_nodata || has;
    }
    if (any_nodata) {
      o->padfSrcNoDataReal = static_cast<double*>(CPLMalloc(sizeof(double) * colour_bands));
      std::copy(nodata.begin(), nodata.end(), o->padfSrcNoDataReal);
      if (colour_bands > 1)
        o->papszWarpOptions = CSLSetNameValue(o->papszWarpOptions, "UNIFIED_SRC_NODATA", "PARTIAL");
    }
    if (spec_.nan_nodata) {
      o->padfDstNoDataReal = static_cast<double*>(CPLMalloc(sizeof(double) * colour_bands));
      for (int b = 0; b < colour_bands; ++b)
        o->padfDstNoDataReal[b] = std::numeric_limits<double>::quiet_NaN();
    }
    op->operation = GDALCreateWarpOperation(o);
    if (!op->operation)
      throw InputError(src.name() + ": cannot set up warping (" + gdal_last_error() + ")");
    ops.push_back(std::move(op));
  }
  return ops;
}

void RasterWarper::io(GDALRWFlag flag, int w, int h, void* data, const std::string& what) {
  std::vector<int> bands(spec_.bands);
  std::iota(bands.begin(), bands.end(), 1);
  const int size = GDALGetDataTypeSizeBytes(spec_.type);
  if (GDALDatasetRasterIO(dest_.get(), flag, 0, 0, w, h, data, w, h, spec_.type, spec_.bands,
                          bands.data(), size, GSpacing(size) * w,
                          GSpacing(size) * w * h) != CE_None)
    throw InputError(what + ": " + (flag == GF_Read ? "reading" : "initialising") +
                     " the warp buffer failed (" + gdal_last_error() + ")");
}

void RasterWarper::warp(const std::array<double, 6>& window_gt, int w, int h,
                        const std::string& what, void* data) {
  if (w < 1 || h < 1 || w > spec_.max_width || h > spec_.max_height)
    throw std::invalid_argument("RasterWarper: window of " + std::to_string(w) + " x " +
                                std::to_string(h) + " pixels");
  std::array<double, 6> gt = window_gt;
  // Initialised here, not by GDAL per source (INIT_DEST would let a later
  // source's window wipe what an earlier source wrote: mosaics, +-360 copies).
  io(GF_Write, w, h, data, what);

  const double min_x = gt[0], max_x = gt[0] + w * gt[1], half = tileformat::kWebMercatorHalf;
  const bool at_antimeridian =
      spec_.tiling.scheme == "webmercator" && (min_x < -half + gt[1] || max_x > half - gt[1]);
  // Fresh warp operations for every window: GDAL's operations keep state
  // from earlier windows (reused ones made image tiles depend on which
  // windows a warper had done before, i.e. on the thread count). Setting one
  // up costs far less than the warp.
  if (at_antimeridian) {
    // The same projection up to a shift in x (with +over, longitudes continue
    // past +-180), but the window stays away from the wrap.
    const double centre_lon = (min_x + max_x) / 2 / half * 180.0;
    const SpatialRef crs = SpatialRef::from_user_input(
        "+proj=merc +a=6378137 +b=6378137 +lat_ts=0 +lon_0=" +
            std::string(CPLSPrintf("%.17g", centre_lon)) +
            " +x_0=0 +y_0=0 +k=1 +units=m +nadgrids=@null +over +wktext +no_defs",
        "window CRS");
    gt[0] -= centre_lon / 180.0 * half;
    GDALSetSpatialRef(dest_.get(), crs.get());
  } else {
    GDALSetSpatialRef(dest_.get(), target_.get());
  }
  GDALSetGeoTransform(dest_.get(), gt.data());
  const std::vector<std::unique_ptr<Operation>> ops = make_operations();
  CPLErrorReset();
  for (const auto& op : ops) {
    if (GDALChunkAndWarpImage(op->operation, 0, 0, w, h) != CE_None ||
        CPLGetLastErrorType() == CE_Failure)
      throw InputError(inputs_ + ": reading data for " + what + " failed (" + gdal_last_error() +
                       "); the file may be truncated or corrupt");
  }
  io(GF_Read, w, h, data, what);
}

}  // namespace globe
