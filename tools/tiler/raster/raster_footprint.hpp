// Where raster inputs lie in a tiling, shared by the terrain and imagery
// plans: each source's georeferencing (checked, with errors naming the file),
// copies shifted by +-360 degrees for geographic data past the antimeridian,
// the tiling itself (fixed, derived for `local`, or adopted with --like), the
// areas in the tiling CRS that hold data, their lon/lat bounds, the finest
// source pixel size in tiling units, and the zoom range that follows.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "geo/gdal_dataset.hpp"
#include "geo/spatial_ref.hpp"
#include "kit/build_options.hpp"
#include "tileformat/tiling.hpp"

namespace globe {

struct RasterSource {
  std::string path;
  std::string crs_wkt;  // resolved CRS (the file's or --s_srs)
  std::array<double, 6> geotransform{};
  int width = 0, height = 0;
  std::vector<double> x_shifts;  // 0, and +-360 copies for geographic data past +-180
  bool has_mask_band = false;    // a mask of its own (not alpha or nodata)
  unsigned long long file_bytes = 0;
};

// The longitude shifts at which a warp draws a source, in drawing order. A
// geographic source spanning at most 360 degrees is drawn once: GDAL wraps
// longitudes around its centre (gdalwarp's CENTER_LONG). A wider one (a
// 0..360 grid with an overlapping column, a grid-registered global grid)
// gets its +-360 copies first and the source itself last, so that where
// they overlap the source's own pixels win, as in gdalwarp of the source.
std::vector<double> warp_shifts(const RasterSource& src);

// A geographic source whose columns go once around the Earth: its number of
// distinct columns n (360 / step), when it has n (e.g. ETOPO5's 4,320 from
// -180.0417) or n + 1, the last repeating the first (grid-registered, e.g.
// etopo20's 1,081); else 0 (also for a source with a mask band of its own,
// which the periodic VRT would not carry). Such a source is warped as its
// periodic extension, drawn once.
int periodic_columns(const RasterSource& src);
// Columns added on each side of such a source (more than any kernel's reach).
constexpr int kWrapColumns = 8;

// A VRT copy of `in` (the opened `src`)
// that carries the source's resolved georeferencing with its longitudes shifted by `shift`
// (a source once around the Earth extended by kWrapColumns wrapped columns each side), and
// `nodata` on `nodata_bands` — never written back to the file. What each warp source is built from.
// Throws InputError (cannot wrap) or OutputError (GDAL refused a setting).
GdalDataset georeferenced_copy(GDALDatasetH in, const RasterSource& src, double shift,
                               std::optional<double> nodata, const std::vector<int>& nodata_bands);

// --tiling, --t_srs and --like together; throws UsageError. (plan_footprint
// checks again; commands call this before opening any input.)
void check_tiling_options(const BuildOptions& s, const std::string& like);

// The georeferencing of an opened raster; `s_srs` replaces the file's CRS.
// Throws InputError (no geotransform, rotated, no CRS).
RasterSource describe_raster(const GdalDataset& ds, const std::string& path,
                             const std::optional<SpatialRef>& s_srs);

// How a tile's pixels sit on it: terrain samples put the first pixel centre on
// the tile's corner (neighbours share edge samples); image pixels are areas
// that fill the tile exactly.
struct TileGrid {
  int pixels = 256;  // pixel spacing = tile edge / pixels
  bool centres_on_corners = false;
};

// The part of a terrain or imagery plan that says where the data lies; both
// plans derive from it.
struct Footprint {
  tileformat::Tiling tiling;
  std::vector<tileformat::Bounds> data_areas;  // tiling CRS, clipped to its extent
  tileformat::Bounds lonlat;                   // data bounds in degrees (metadata)
  double source_resolution = 0;                // finest source pixel, tiling units
  int natural_max_zoom = 0;                    // first zoom whose pixels reach it
  int min_zoom = 0, max_zoom = 0;              // --min-zoom/--max-zoom or the defaults
  // What part of the inputs the tiling cannot hold (webmercator ends at
  // +-85.0511 degrees), in words; "" if none. Goes to metadata and `info`.
  std::string left_out;
};

// Checks --tiling/--t_srs, fills each source's x_shifts, places the data and
// picks the zoom range (--max-zoom at most 6 deeper than the natural finest
// zoom). `like`: a package whose tiling is adopted ("" for none). Throws
// InputError or UsageError.
Footprint plan_footprint(std::vector<RasterSource>& sources, const BuildOptions& s,
                         const std::string& like, TileGrid grid);

}  // namespace globe
