// Imagery from foreign tile servers (see remote_image_reader.hpp).
#include "data/remote_image_reader.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "runtime/errors.hpp"
#include "tileformat/error.hpp"
#include "tileformat/image_tile.hpp"
#include "tileformat/metadata.hpp"

namespace globe::viewer {
namespace {

using tileformat::TileId;

// Web mercator tile coordinates of a longitude / latitude at zoom z.
double tile_x(double lon, int z) {
  return (lon + 180) / 360 * double(uint64_t{1} << z);
}
double tile_y(double lat, int z) {
  const double clamped = std::clamp(lat, -85.0511287798, 85.0511287798) * std::numbers::pi / 180;
  return (1 - std::log(std::tan(clamped) + 1 / std::cos(clamped)) / std::numbers::pi) / 2 *
         double(uint64_t{1} << z);
}

struct Range {
  uint32_t x0, x1, y0, y1;
};
Range range_of(int z, const std::array<double, 4>& b) {
  const double n = double(uint64_t{1} << z);
  const auto cell = [&](double v) { return uint32_t(std::clamp(std::floor(v), 0.0, n - 1)); };
  return {cell(tile_x(b[0], z)), cell(tile_x(b[2], z) - 1e-9), cell(tile_y(b[3], z)),
          cell(tile_y(b[1], z) - 1e-9)};
}

}  // namespace

bool webmercator_tile_in(TileId id, const std::array<double, 4>& bounds) {
  const Range r = range_of(id.z, bounds);
  return id.x >= r.x0 && id.x <= r.x1 && id.y >= r.y0 && id.y <= r.y1;
}

std::vector<TileId> webmercator_tiles_in(int z, const std::array<double, 4>& bounds) {
  const Range r = range_of(z, bounds);
  const uint64_t w = uint64_t(r.x1) - r.x0 + 1, h = uint64_t(r.y1) - r.y0 + 1;
  const uint64_t stride = std::max<uint64_t>(1, (w * h + 65535) / 65536);
  std::vector<TileId> out;
  for (uint64_t i = 0; i < w * h; i += stride)
    out.push_back({z, uint32_t(r.x0 + i % w), uint32_t(r.y0 + i / w)});
  return out;
}

RemoteImageReader::RemoteImageReader(std::unique_ptr<RasterTileFetcher> fetcher)
    : fetcher_(std::move(fetcher)) {
  tileformat::ImageMetadata m;
  m.common.tiling = tileformat::Tiling::webmercator();
  m.common.min_zoom = fetcher_->min_zoom();
  m.common.max_zoom = fetcher_->max_zoom();
  const auto b = fetcher_->bounds();
  m.common.lonlat = {b[0], b[1], b[2], b[3]};
  m.common.center_zoom = m.common.min_zoom;
  m.common.name = fetcher_->name();
  m.common.description = "imagery streamed from " + fetcher_->name();
  m.common.type = "baselayer";
  // The first tile that can be read says the format, size and colour.
  std::string why = "no tile at zoom " + std::to_string(m.common.min_zoom);
  bool found = false;
  for (const TileId& id : webmercator_tiles_in(m.common.min_zoom, b)) {
    try {
      const auto blob = fetcher_->fetch(id);
      if (!blob) continue;
      const tileformat::ImageHeader h = tileformat::inspect_image_tile(*blob);
      m.format = h.format;
      m.tile_size = h.width;
      m.colour_bands = h.channels == 1 || h.channels == 2 ? 1 : 3;
      found = true;
      break;
    } catch (const std::exception& e) {
      why = e.what();
    }
    if (found) break;
  }
  if (!found) throw InputError(fetcher_->name() + ": no image tile could be read (" + why + ")");
  m.common.format = tileformat::image_format_name(m.format);
  metadata_ = tileformat::to_metadata(m);
}

std::optional<std::vector<uint8_t>> RemoteImageReader::tile(TileId id) {
  return fetcher_->fetch(id);
}

bool RemoteImageReader::has_tile(TileId id) {
  return id.z >= fetcher_->min_zoom() && id.z <= fetcher_->max_zoom() &&
         webmercator_tile_in(id, fetcher_->bounds());
}

std::vector<TileId> RemoteImageReader::tile_ids(int zoom) {
  if (zoom < fetcher_->min_zoom() || zoom > fetcher_->max_zoom()) return {};
  return webmercator_tiles_in(zoom, fetcher_->bounds());
}

}  // namespace globe::viewer
