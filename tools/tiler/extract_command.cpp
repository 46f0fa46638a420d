// `globe-tiler extract PACKAGE --zoom Z [--bbox W,S,E,N] -o OUT.tif`: the
// decoded heights of one zoom as a GeoTIFF in the tiling CRS (pixel centres on
// the block samples), so GDAL can check the package against its sources.
#include <cpl_conv.h>
#include <cpl_string.h>
#include <gdal.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>

#include "cli_args.hpp"
#include "commands.hpp"
#include "errors.hpp"
#include "gdal_dataset.hpp"
#include "spatial_ref.hpp"
#include "terrain_package.hpp"
#include "tileformat/error.hpp"
#include "tileformat/mblock.hpp"

namespace globe {

int run_extract(const std::vector<std::string>& args) {
  std::optional<int> zoom;
  std::optional<std::vector<double>> bbox;
  std::string output;
  bool force = false;
  CliArgs cli("globe-tiler extract",
              "globe-tiler extract PACKAGE --zoom Z [--bbox W,S,E,N] -o OUT.tif\n\n"
              "Writes the decoded heights of one zoom as a Float64 GeoTIFF in the tiling CRS;\n"
              "samples without data are NaN (nodata).");
  cli.option("--zoom", "Z", "zoom level to extract",
             [&](const std::string& v) { zoom = CliArgs::to_int("--zoom", v, 0, 30); });
  cli.option("--bbox", "W,S,E,N", "only tiles intersecting this lon/lat box",
             [&](const std::string& v) { bbox = CliArgs::to_doubles("--bbox", v, 4); });
  cli.option("-o,--output", "OUT.tif", "output GeoTIFF", [&](const std::string& v) { output = v; });
  cli.flag("--force", "replace an existing output", [&] { force = true; });
  auto positional = cli.parse_command(args, 1, 1, "PACKAGE");
  if (!positional) return kExitOk;
  if (!zoom) throw UsageError("--zoom is required");
  if (output.empty()) throw UsageError("no output given; add -o OUT.tif");
  const std::string& path = (*positional)[0];
  TerrainPackage p = open_terrain_package(path);
  if (*zoom < p.min_zoom || *zoom > p.max_zoom)
    throw UsageError("--zoom " + std::to_string(*zoom) + " is out of range: " + path +
                     " holds zooms " + std::to_string(p.min_zoom) + ".." +
                     std::to_string(p.max_zoom));
  std::error_code ec;
  if (std::filesystem::exists(output, ec) && !force)
    throw OutputError(output + ": output exists; pass --force to replace it");

  gdal_init();
  // Tiles of the zoom, optionally limited to the bbox.
  std::vector<tileformat::TileId> ids;
  std::optional<tileformat::Bounds> area;
  if (bbox) {
    const SpatialRef ll = SpatialRef::from_user_input("EPSG:4326", "internal");
    const SpatialRef target = SpatialRef::from_user_input(p.tiling.crs, path);
    tileformat::Bounds b{(*bbox)[0], (*bbox)[1], (*bbox)[2], (*bbox)[3]}, out;
    CoordTransform t(ll, target);
    if (!t.transform_bounds(b, out))
      throw UsageError("--bbox cannot be transformed to the tiling CRS");
    area = out;
  }
  p.reader->for_each_tile(
      [&](tileformat::TileId id, std::span<const uint8_t>) {
        if (!area || p.tiling.tile_bounds(id).intersects(*area)) ids.push_back(id);
      },
      *zoom);
  if (ids.empty())
    throw InputError(path + ": no tiles at zoom " + std::to_string(*zoom) +
                     (bbox ? " inside --bbox" : ""));
  uint32_t x0 = ids[0].x, x1 = x0, y0 = ids[0].y, y1 = y0;
  for (const auto& id : ids) {
    x0 = std::min(x0, id.x);
    x1 = std::max(x1, id.x);
    y0 = std::min(y0, id.y);
    y1 = std::max(y1, id.y);
  }
  const int n = p.block_size - 1;
  const uint64_t w = uint64_t(x1 - x0 + 1) * n + 1, h = uint64_t(y1 - y0 + 1) * n + 1;
  if (w > 1000000 || h > 1000000)
    throw UsageError("the extract would be " + std::to_string(w) + " x " + std::to_string(h) +
                     " pixels; limit it with --bbox");
  const double sp = p.tiling.sample_spacing(*zoom, n);
  const auto corner = p.tiling.tile_bounds({*zoom, x0, y0});
  double gt[6] = {corner.min_x - sp / 2, sp, 0, corner.max_y + sp / 2, 0, -sp};

  const std::string temp = output + ".tmp.tif";
  char** opts = nullptr;
  opts = CSLSetNameValue(opts, "TILED", "YES");
  opts = CSLSetNameValue(opts, "COMPRESS", "DEFLATE");
  opts = CSLSetNameValue(opts, "BIGTIFF", "IF_SAFER");
  GDALDatasetH ds = GDALCreate(GDALGetDriverByName("GTiff"), temp.c_str(), static_cast<int>(w),
                               static_cast<int>(h), 1, GDT_Float64, opts);
  CSLDestroy(opts);
  if (!ds) throw OutputError(output + ": cannot create the GeoTIFF (" + gdal_last_error() + ")");
  GdalDataset out(ds, temp);
  GDALSetGeoTransform(ds, gt);
  const SpatialRef crs = SpatialRef::from_user_input(p.tiling.crs, path);
  GDALSetSpatialRef(ds, crs.get());
  const double nan = std::numeric_limits<double>::quiet_NaN();
  GDALSetRasterNoDataValue(out.band(1), nan);
  GDALFillRaster(out.band(1), nan, 0);
  std::vector<double> buf(size_t(n + 1) * (n + 1));
  for (const auto& id : ids) {
    tileformat::MBlock b;
    try {
      b = tileformat::decode_mblock(*p.reader->tile(id));
    } catch (const tileformat::FormatError& e) {
      std::filesystem::remove(temp, ec);
      throw InputError(path + ": tile " + id.str() + ": " + e.what());
    }
    for (int y = 0; y <= n; ++y)
      for (int x = 0; x <= n; ++x)
        buf[size_t(y) * (n + 1) + x] = b.is_valid(x, y) ? b.height(x, y) : nan;
    if (GDALRasterIO(out.band(1), GF_Write, int(id.x - x0) * n, int(id.y - y0) * n, n + 1, n + 1,
                     buf.data(), n + 1, n + 1, GDT_Float64, 0, 0) != CE_None) {
      std::filesystem::remove(temp, ec);
      throw OutputError(output + ": write failed (" + gdal_last_error() + ")");
    }
  }
  out = GdalDataset();  // close and flush
  std::filesystem::rename(temp, output, ec);
  if (ec) throw OutputError(output + ": cannot rename into place: " + ec.message());
  std::fprintf(stderr, "globe-tiler: wrote %s: %llu x %llu samples from %zu tiles of zoom %d\n",
               output.c_str(), static_cast<unsigned long long>(w),
               static_cast<unsigned long long>(h), ids.size(), *zoom);
  return kExitOk;
}

}  // namespace globe
