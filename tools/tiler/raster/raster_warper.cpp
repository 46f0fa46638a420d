// Windowed warping through GDAL's warp kernel (see raster_warper.hpp).
#include "raster/raster_warper.hpp"

#include <cpl_string.h>
#include <gdal_alg.h>
#include <gdalwarper.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <optional>

#include "geo/spatial_ref.hpp"
#include "raster/window_coordinates.hpp"
#include "runtime/errors.hpp"

namespace globe {
namespace {

struct Algorithm {
  const char* name;
  GDALResampleAlg alg;
  int radius;  // source pixels the kernel reaches at scale 1 (GDAL's filter radius)
};
constexpr Algorithm kAlgs[] = {{"near", GRA_NearestNeighbour, 0},
                               {"bilinear", GRA_Bilinear, 1},
                               {"cubic", GRA_Cubic, 2},
                               {"cubicspline", GRA_CubicSpline, 2},
                               {"lanczos", GRA_Lanczos, 3},
                               {"average", GRA_Average, 0},
                               {"min", GRA_Min, 0},
                               {"max", GRA_Max, 0},
                               {"med", GRA_Med, 0},
                               {"mode", GRA_Mode, 0}};

const Algorithm& algorithm(const std::string& name) {
  for (const auto& a : kAlgs)
    if (name == a.name) return a;
  throw UsageError("--resampling: '" + name + "' is not one of " + kResamplingNames);
}

int* band_list(int n) {
  int* list = static_cast<int*>(CPLMalloc(sizeof(int) * n));
  std::iota(list, list + n, 1);
  return list;
}

// GDAL's kernel scale for `step` source pixels per destination pixel: 1 when
// upsampling, else the reciprocal, snapped to 1/n when close (as GDAL does).
double kernel_scale(double step) {
  if (!(step > 1)) return 1.0;
  const double n = std::round(step);
  return std::abs(step - n) < 0.05 ? 1.0 / n : 1.0 / step;
}

}  // namespace

const char* const kResamplingNames =
    "near, bilinear, cubic, cubicspline, lanczos, average, min, max, med, mode";

bool is_resampling(const std::string& name) {
  return std::any_of(std::begin(kAlgs), std::end(kAlgs),
                     [&](const Algorithm& a) { return name == a.name; });
}

// The transformer the kernel calls: rows of the current window's pixel
// centres come from WindowCoordinates, anything else (single points GDAL
// re-checks, pixel corners for `average`) from the exact transformer.
struct RasterWarper::Source {
  GDALDatasetH ds = nullptr;
  void* exact = nullptr;  // GenImgProj transformer, destination pixel -> source pixel
  GDALWarpOptions* options = nullptr;
  const WindowCoordinates* window = nullptr;
  int radius = 0;

  ~Source() {
    if (options) {
      options->pTransformerArg = nullptr;
      GDALDestroyWarpOptions(options);
    }
    if (exact) GDALDestroyGenImgProjTransformer(exact);
  }

  static int transform(void* arg, int dst_to_src, int n, double* x, double* y, double* z, int* ok) {
    auto* self = static_cast<Source*>(arg);
    const WindowCoordinates* win = self->window;
    if (dst_to_src && win && n == win->width()) {
      const double row = y[0] - 0.5;
      bool is_row = row >= 0 && row < win->height() && row == std::floor(row);
      for (int i = 0; i < n && is_row; ++i)
        is_row = x[i] == i + 0.5 && y[i] == y[0];
      if (is_row) {
        win->row(static_cast<int>(row), x, y, ok);
        std::fill(z, z + n, 0.0);
        return TRUE;
      }
    }
    return GDALGenImgProjTransform(self->exact, dst_to_src, n, x, y, z, ok);
  }
};

RasterWarper::RasterWarper(std::vector<GdalDataset> sources, WarpSpec spec, std::string inputs)
    : datasets_(std::move(sources)), spec_(std::move(spec)), inputs_(std::move(inputs)) {
  const Algorithm& alg = algorithm(spec_.resampling);
  const int colour_bands = spec_.bands - (spec_.alpha ? 1 : 0);
  CPLStringList transformer_options;
  transformer_options.SetNameValue("DST_SRS", spec_.target_crs.c_str());
  for (auto& ds : datasets_) {
    auto src = std::make_unique<Source>();
    src->ds = ds.get();
    src->radius = alg.radius;
    CPLErrorReset();
    // As gdalwarp: a geographic source spanning at most 360 degrees gets
    // CENTER_LONG, so longitudes wrap around its centre.
    src->exact = GDALCreateGenImgProjTransformer2(ds.get(), nullptr, transformer_options.List());
    if (!src->exact)
      throw InputError(ds.name() + ": no transformation to the tiling CRS (" + gdal_last_error() +
                       ")");
    GDALWarpOptions* o = GDALCreateWarpOptions();
    src->options = o;
    o->pfnTransformer = &Source::transform;
    o->pTransformerArg = src.get();
    o->hSrcDS = ds.get();
    o->nBandCount = colour_bands;
    o->panSrcBands = band_list(colour_bands);
    o->panDstBands = band_list(colour_bands);
    const int src_bands = ds.bands();
    if (spec_.alpha) {
      o->nDstAlphaBand = spec_.bands;
      if (src_bands == colour_bands + 1 &&
          GDALGetRasterColorInterpretation(ds.band(src_bands)) == GCI_AlphaBand)
        o->nSrcAlphaBand = src_bands;
    }
    o->eResampleAlg = alg.alg;
    o->eWorkingDataType = spec_.type;
    o->dfWarpMemoryLimit = 256.0 * 1024 * 1024;
    // Source nodata: a pixel is empty when every band that has a nodata value
    // holds it (PARTIAL; GDAL's default would judge each band on its own).
    bool any_nodata = false;
    std::vector<double> nodata(colour_bands, 0.0);
    for (int b = 0; b < colour_bands; ++b) {
      int has = 0;
      nodata[b] = GDALGetRasterNoDataValue(ds.band(b + 1), &has);
      any_nodata = any_nodata || has;
    }
    if (any_nodata) {
      o->padfSrcNoDataReal = static_cast<double*>(CPLMalloc(sizeof(double) * colour_bands));
      std::copy(nodata.begin(), nodata.end(), o->padfSrcNoDataReal);
      if (colour_bands > 1)
        o->papszWarpOptions = CSLSetNameValue(o->papszWarpOptions, "UNIFIED_SRC_NODATA", "PARTIAL");
    }
    sources_.push_back(std::move(src));
  }
}

RasterWarper::~RasterWarper() = default;

void RasterWarper::warp(const std::array<double, 6>& gt, int w, int h, const std::string& what,
                        void* data) {
  if (w < 1 || h < 1 || w > spec_.max_width || h > spec_.max_height)
    throw std::invalid_argument("RasterWarper: window of " + std::to_string(w) + " x " +
                                std::to_string(h) + " pixels");
  for (auto& src : sources_) {
    GDALSetGenImgProjTransformerDstGeoTransform(src->exact, gt.data());
    warp_source(*src, w, h, what, data);
  }
}

void RasterWarper::warp_source(Source& src, int w, int h, const std::string& what, void* data) {
  const int sw = GDALGetRasterXSize(src.ds), sh = GDALGetRasterYSize(src.ds);
  // Coordinates first (exact, wherever the window lies), then the window of
  // source pixels the kernel can reach. The reach assumes no more than 64
  // source pixels per destination pixel, far beyond what tiling asks.
  const double reach = (src.radius + 1) * 64.0;
  const WindowCoordinates coords(GDALGenImgProjTransform, src.exact, w, h, spec_.tolerance_px,
                                 {-reach, -reach, sw + reach, sh + reach});
  const WindowCoordinates::Extent& e = coords.extent();
  if (e.empty()) return;  // the window lies outside this source
  const double step_x = coords.source_step_x(), step_y = coords.source_step_y();
  const double scale_x = kernel_scale(step_x), scale_y = kernel_scale(step_y);
  const int rx = static_cast<int>(std::ceil((src.radius + 1) / scale_x)) + 1;
  const int ry = static_cast<int>(std::ceil((src.radius + 1) / scale_y)) + 1;
  const int x0 = std::max(0, static_cast<int>(std::floor(e.min_x)) - rx);
  const int y0 = std::max(0, static_cast<int>(std::floor(e.min_y)) - ry);
  const int x1 = std::min(sw, static_cast<int>(std::ceil(e.max_x)) + rx);
  const int y1 = std::min(sh, static_cast<int>(std::ceil(e.max_y)) + ry);
  if (x0 >= x1 || y0 >= y1) return;

  GDALWarpOptions* o = src.options;
  if (step_x > 0)
    o->papszWarpOptions =
        CSLSetNameValue(o->papszWarpOptions, "XSCALE", CPLSPrintf("%.17g", scale_x));
  if (step_y > 0)
    o->papszWarpOptions =
        CSLSetNameValue(o->papszWarpOptions, "YSCALE", CPLSPrintf("%.17g", scale_y));
  // The alpha band is read and written through a dataset: a MEM dataset
  // whose bands are the planes of `data`.
  GdalDataset window;
  if (spec_.alpha) {
    window = GdalDataset(GDALCreate(GDALGetDriverByName("MEM"), "", w, h, 0, spec_.type, nullptr),
                         "window");
    if (!window.get())
      throw std::runtime_error("cannot create the warp window: " + gdal_last_error());
    const size_t plane = size_t(GDALGetDataTypeSizeBytes(spec_.type)) * w * h;
    for (int b = 0; b < spec_.bands; ++b) {
      char pointer[64] = {};
      CPLPrintPointer(pointer, static_cast<uint8_t*>(data) + b * plane, sizeof pointer);
      CPLStringList band_options;
      band_options.SetNameValue("DATAPOINTER", pointer);
      if (GDALAddBand(window.get(), spec_.type, band_options.List()) != CE_None)
        throw std::runtime_error("cannot create the warp window: " + gdal_last_error());
    }
    gdal_check(GDALSetRasterColorInterpretation(window.band(spec_.bands), GCI_AlphaBand),
               "marking the window's alpha band");
  }
  o->hDstDS = window.get();

  src.window = &coords;
  CPLErrorReset();
  GDALWarpOperationH op = GDALCreateWarpOperation(o);
  if (!op) {
    src.window = nullptr;
    o->hDstDS = nullptr;
    throw InputError(inputs_ + ": cannot set up warping for " + what + " (" + gdal_last_error() +
                     ")");
  }
  // Points outside a projection's domain only leave their pixels empty (PROJ
  // may log them; that is not a failure). What fails here is reading.
  const CPLErr err =
      GDALWarpRegionToBuffer(op, 0, 0, w, h, data, spec_.type, x0, y0, x1 - x0, y1 - y0);
  const std::string why = err != CE_None ? gdal_last_error() : std::string();
  GDALDestroyWarpOperation(op);
  src.window = nullptr;
  o->hDstDS = nullptr;
  if (err != CE_None) {
    // A failure that names PROJ is a coordinate operation, not the file.
    const bool projection = why.find("PROJ") != std::string::npos;
    throw InputError(inputs_ + ": " + (projection ? "reprojecting" : "reading") + " data for " +
                     what + " failed (" + why + ")" +
                     (projection ? "; check the input's CRS (or --s_srs)"
                                 : "; the file may be truncated or corrupt"));
  }
}

}  // namespace globe
