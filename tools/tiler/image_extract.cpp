// `globe-tiler extract` for image packages: the tile pixels of one zoom as a
// Byte GeoTIFF (gray or RGB, then alpha) whose pixels are the tiles' pixels.
#include <gdal.h>

#include <cstdio>

#include "errors.hpp"
#include "image_codec.hpp"
#include "image_package.hpp"
#include "inspect_commands.hpp"
#include "tileformat/error.hpp"

namespace globe {

int extract_image(const ExtractRequest& rq) {
  const std::string& path = rq.package;
  ImagePackage p = open_image_package(path);
  if (rq.zoom < p.min_zoom || rq.zoom > p.max_zoom)
    throw UsageError("--zoom " + std::to_string(rq.zoom) + " is out of range: " + path +
                     " holds zooms " + std::to_string(p.min_zoom) + ".." +
                     std::to_string(p.max_zoom));
  const std::vector<tileformat::TileId> ids = tiles_to_extract(*p.reader, p.tiling, rq);
  uint32_t x0 = ids[0].x, x1 = x0, y0 = ids[0].y, y1 = y0;
  for (const auto& id : ids) {
    x0 = std::min(x0, id.x);
    x1 = std::max(x1, id.x);
    y0 = std::min(y0, id.y);
    y1 = std::max(y1, id.y);
  }
  const int n = p.tile_size;
  const uint64_t w = uint64_t(x1 - x0 + 1) * n, h = uint64_t(y1 - y0 + 1) * n;
  if (w > 200000 || h > 200000)
    throw UsageError("the extract would be " + std::to_string(w) + " x " + std::to_string(h) +
                     " pixels; limit it with --bbox");
  const double px = p.tiling.sample_spacing(rq.zoom, n);
  const auto corner = p.tiling.tile_bounds({rq.zoom, x0, y0});
  const double gt[6] = {corner.min_x, px, 0, corner.max_y, 0, -px};
  const int bands = p.colour + 1;
  ExtractTiff out(rq, static_cast<int>(w), static_cast<int>(h), bands, GDT_Byte, gt, p.tiling.crs);
  auto ds = static_cast<GDALDatasetH>(out.handle());
  const GDALColorInterp colours[] = {GCI_RedBand, GCI_GreenBand, GCI_BlueBand};
  for (int b = 1; b <= p.colour; ++b)
    GDALSetRasterColorInterpretation(GDALGetRasterBand(ds, b),
                                     p.colour == 1 ? GCI_GrayIndex : colours[b - 1]);
  GDALSetRasterColorInterpretation(GDALGetRasterBand(ds, bands), GCI_AlphaBand);
  for (const auto& id : ids) {
    TilePixels tile;
    try {
      tile = decode_image_tile(*p.reader->tile(id), n, p.colour);
    } catch (const tileformat::FormatError& e) {
      throw InputError(path + ": tile " + id.str() + ": " + e.what());
    }
    for (int b = 0; b < bands; ++b)
      out.write(b + 1, int(id.x - x0) * n, int(id.y - y0) * n, n, n, tile.plane(b), GDT_Byte);
  }
  out.commit();
  std::fprintf(stderr, "globe-tiler: wrote %s: %llu x %llu pixels from %zu tiles of zoom %d\n",
               rq.output.c_str(), static_cast<unsigned long long>(w),
               static_cast<unsigned long long>(h), ids.size(), rq.zoom);
  return kExitOk;
}

}  // namespace globe
