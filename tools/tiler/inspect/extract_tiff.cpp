// What every raster kind's `globe-tiler extract` shares: the tiles of the
// zoom (inside --bbox), block samples written as one GeoTIFF band, and the
// GeoTIFF written under a temporary name until committed.
#include <filesystem>
#include <limits>

#include "geo/gdal_dataset.hpp"
#include "geo/spatial_ref.hpp"
#include "inspect/inspect_commands.hpp"
#include "runtime/errors.hpp"

namespace globe {

using tileformat::TileId;
SampleGrid write_block_samples(
    const ExtractRequest& rq, const tileformat::Tiling& tiling, const ExtractTiles& t,
    int block_size, GDALDataType type,
    const std::function<void(TileId, std::vector<double>& samples)>& fill) {
  const int n = block_size - 1;
  const uint64_t w = uint64_t(t.cols) * n + 1, h = uint64_t(t.rows) * n + 1;
  if (w > 1000000 || h > 1000000)
    throw UsageError("the extract would be " + std::to_string(w) + " x " + std::to_string(h) +
                     " pixels; limit it with --bbox");
  const double sp = tiling.sample_spacing(rq.zoom, n);
  const auto corner = tiling.tile_bounds({rq.zoom, t.x0, t.y0});
  const std::array<double, 6> gt{corner.min_x - sp / 2, sp, 0, corner.max_y + sp / 2, 0, -sp};
  ExtractTiff out(rq, static_cast<int>(w), static_cast<int>(h), 1, type, gt, tiling.crs);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  out.dataset().set_nodata(1, nan);
  out.dataset().fill(1, nan);
  std::vector<double> samples(size_t(block_size) * block_size);
  for (const TileId& id : t.ids) {
    fill(id, samples);
    out.dataset().write(1, int(id.x - t.x0) * n, int(id.y - t.y0) * n, block_size, block_size,
                        samples.data(), GDT_Float64);
  }
  out.commit();
  return {static_cast<int>(w), static_cast<int>(h)};
}

ExtractTiles tiles_to_extract(tileformat::PackageReader& reader, const tileformat::Tiling& tiling,
                              const ExtractRequest& rq, int min_zoom, int max_zoom) {
  if (rq.zoom < min_zoom || rq.zoom > max_zoom)
    throw UsageError("--zoom " + std::to_string(rq.zoom) + " is out of range: " + rq.package +
                     " holds zooms " + std::to_string(min_zoom) + ".." + std::to_string(max_zoom));
  std::optional<tileformat::Bounds> area;
  if (rq.bbox) {
    const SpatialRef ll = SpatialRef::from_user_input("EPSG:4326", "internal");
    const SpatialRef target = SpatialRef::from_user_input(tiling.crs, rq.package);
    tileformat::Bounds b{(*rq.bbox)[0], (*rq.bbox)[1], (*rq.bbox)[2], (*rq.bbox)[3]}, out;
    CoordTransform t(ll, target);
    if (!t.transform_bounds(b, out))
      throw UsageError("--bbox cannot be transformed to the tiling CRS");
    area = out;
  }
  std::vector<tileformat::TileId> ids;
  reader.for_each_tile(
      [&](tileformat::TileId id, std::span<const uint8_t>) {
        if (!area || tiling.tile_bounds(id).intersects(*area)) ids.push_back(id);
      },
      rq.zoom);
  if (ids.empty())
    throw InputError(rq.package + ": no tiles at zoom " + std::to_string(rq.zoom) +
                     (rq.bbox ? " inside --bbox" : ""));
  ExtractTiles t;
  uint32_t x1 = ids[0].x, y1 = ids[0].y;
  t.x0 = x1;
  t.y0 = y1;
  for (const auto& id : ids) {
    t.x0 = std::min(t.x0, id.x);
    x1 = std::max(x1, id.x);
    t.y0 = std::min(t.y0, id.y);
    y1 = std::max(y1, id.y);
  }
  t.cols = x1 - t.x0 + 1;
  t.rows = y1 - t.y0 + 1;
  t.ids = std::move(ids);
  return t;
}

ExtractTiff::ExtractTiff(const ExtractRequest& rq, int width, int height, int bands,
                         GDALDataType type, const std::array<double, 6>& gt,
                         const std::string& crs_text)
    : output_(rq.output), temp_(rq.output + ".tmp.tif") {
  ds_ = GdalDataset::create_raster("GTiff", temp_, width, height, bands, type,
                                   {"TILED=YES", "COMPRESS=DEFLATE", "BIGTIFF=IF_SAFER"});
  try {
    ds_.set_geotransform(gt);
    ds_.set_crs(SpatialRef::from_user_input(crs_text, rq.package));
  } catch (...) {  // the destructor does not run for a constructor that throws
    ds_.close();
    std::error_code ec;
    std::filesystem::remove(temp_, ec);
    throw;
  }
}

ExtractTiff::~ExtractTiff() {
  ds_.close();
  std::error_code ec;
  if (!committed_) std::filesystem::remove(temp_, ec);
}

void ExtractTiff::commit() {
  ds_.close();  // flush
  std::error_code ec;
  std::filesystem::rename(temp_, output_, ec);
  if (ec) throw OutputError(output_ + ": cannot rename into place: " + ec.message());
  committed_ = true;
}

}  // namespace globe
