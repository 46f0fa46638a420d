// Spatial reference and transformation wrappers (see spatial_ref.hpp).
#include "geo/spatial_ref.hpp"

#include <cpl_error.h>

#include <algorithm>
#include <cmath>

#include <cpl_conv.h>

#include "geo/gdal_dataset.hpp"
#include "runtime/errors.hpp"

namespace globe {

SpatialRef SpatialRef::from_user_input(const std::string& text, const std::string& context) {
  SpatialRef s;
  s.reset(OSRNewSpatialReference(nullptr));
  CPLErrorReset();
  if (OSRSetFromUserInput(s.h_.get(), text.c_str()) != OGRERR_NONE)
    throw UsageError(context + ": '" + text + "' is not a CRS PROJ knows (" + gdal_last_error() +
                     "); use e.g. EPSG:4326");
  OSRSetAxisMappingStrategy(s.h_.get(), OAMS_TRADITIONAL_GIS_ORDER);
  return s;
}

SpatialRef SpatialRef::from_wkt(const std::string& wkt, const std::string& context) {
  SpatialRef s;
  s.reset(OSRNewSpatialReference(nullptr));
  if (OSRSetFromUserInput(s.h_.get(), wkt.c_str()) != OGRERR_NONE)
    throw InputError(context + ": unreadable CRS definition");
  OSRSetAxisMappingStrategy(s.h_.get(), OAMS_TRADITIONAL_GIS_ORDER);
  return s;
}

std::string SpatialRef::wkt2() const {
  char* wkt = nullptr;
  const char* opts[] = {"FORMAT=WKT2_2018", "MULTILINE=NO", nullptr};
  OSRExportToWktEx(h_.get(), &wkt, opts);
  std::string out = wkt ? wkt : "";
  CPLFree(wkt);
  return out;
}

std::string SpatialRef::name() const {
  const char* auth = OSRGetAuthorityName(h_.get(), nullptr);
  const char* code = OSRGetAuthorityCode(h_.get(), nullptr);
  if (auth && code) return std::string(auth) + ":" + code;
  const char* n = OSRGetName(h_.get());
  return n ? n : "unnamed CRS";
}

CoordTransform::CoordTransform(const SpatialRef& from, const SpatialRef& to) {
  CPLErrorReset();
  h_ = OCTNewCoordinateTransformation(from.get(), to.get());
  if (!h_)
    throw InputError("no coordinate transformation from " + from.name() + " to " + to.name() +
                     " (" + gdal_last_error() + ")");
}

CoordTransform::~CoordTransform() {
  if (h_) OCTDestroyCoordinateTransformation(h_);
}

bool CoordTransform::transform(std::vector<double>& x, std::vector<double>& y) const {
  std::vector<int> ok;
  transform(x, y, ok);
  return std::all_of(ok.begin(), ok.end(), [](int v) { return v != 0; });
}

void CoordTransform::transform(std::vector<double>& x, std::vector<double>& y,
                               std::vector<int>& ok) const {
  ok.assign(x.size(), 0);
  // Points that fail are reported in `ok`; PROJ's message for them is noise.
  CPLPushErrorHandler(CPLQuietErrorHandler);
  OCTTransformEx(h_, static_cast<int>(x.size()), x.data(), y.data(), nullptr, ok.data());
  CPLPopErrorHandler();
  for (size_t i = 0; i < x.size(); ++i)
    ok[i] = ok[i] && std::isfinite(x[i]) && std::isfinite(y[i]);
}

bool CoordTransform::transform_bounds(const tileformat::Bounds& in, tileformat::Bounds& out) const {
  return OCTTransformBounds(h_, in.min_x, in.min_y, in.max_x, in.max_y, &out.min_x, &out.min_y,
                            &out.max_x, &out.max_y, 21) != 0;
}

}  // namespace globe
