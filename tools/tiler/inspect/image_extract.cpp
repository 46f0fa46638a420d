// `globe-tiler extract` for image packages: the tile pixels of one zoom as a
// Byte GeoTIFF (gray or RGB, then alpha) whose pixels are the tiles' pixels.
#include <gdal.h>

#include <cstdio>

#include "geo/gdal_dataset.hpp"
#include "geo/image_codec.hpp"
#include "inspect/inspect_commands.hpp"
#include "runtime/errors.hpp"
#include "runtime/image_package.hpp"
#include "tileformat/error.hpp"

namespace globe {

int extract_image(const ExtractRequest& rq) {
  const std::string& path = rq.package;
  ImagePackage p = open_image_package(path);
  const ExtractTiles t = tiles_to_extract(*p.reader, p.tiling, rq, p.min_zoom, p.max_zoom);
  const auto& ids = t.ids;
  const uint32_t x0 = t.x0, y0 = t.y0;
  const int n = p.tile_size;
  const uint64_t w = uint64_t(t.cols) * n, h = uint64_t(t.rows) * n;
  if (w > 200000 || h > 200000)
    throw UsageError("the extract would be " + std::to_string(w) + " x " + std::to_string(h) +
                     " pixels; limit it with --bbox");
  const double px = p.tiling.sample_spacing(rq.zoom, n);
  const auto corner = p.tiling.tile_bounds({rq.zoom, x0, y0});
  const std::array<double, 6> gt{corner.min_x, px, 0, corner.max_y, 0, -px};
  const int bands = p.colour + 1;
  ExtractTiff out(rq, static_cast<int>(w), static_cast<int>(h), bands, GDT_Byte, gt, p.tiling.crs);
  const GDALColorInterp colours[] = {GCI_RedBand, GCI_GreenBand, GCI_BlueBand};
  for (int b = 1; b <= p.colour; ++b)
    out.dataset().set_colour(b, p.colour == 1 ? GCI_GrayIndex : colours[b - 1]);
  out.dataset().set_colour(bands, GCI_AlphaBand);
  for (const auto& id : ids) {
    TilePixels tile;
    try {
      tile = decode_image_tile(*p.reader->tile(id), n, p.colour);
    } catch (const tileformat::FormatError& e) {
      throw InputError(path + ": tile " + id.str() + ": " + e.what());
    }
    for (int b = 0; b < bands; ++b)
      out.dataset().write(b + 1, int(id.x - x0) * n, int(id.y - y0) * n, n, n, tile.plane(b),
                          GDT_Byte);
  }
  out.commit();
  std::fprintf(stderr, "globe-tiler: wrote %s: %llu x %llu pixels from %zu tiles of zoom %d\n",
               rq.output.c_str(), static_cast<unsigned long long>(w),
               static_cast<unsigned long long>(h), ids.size(), rq.zoom);
  return kExitOk;
}

}  // namespace globe
