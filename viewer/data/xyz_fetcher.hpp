// XyzFetcher: raster tiles from an XYZ URL template, the way the web's
// tile servers publish them — `https://HOST/{z}/{x}/{y}.png` (row 0 at the
// north), `{-y}` for TMS rows (row 0 at the south) — for imagery and, with
// --dem-encoding, Terrarium or Terrain-RGB elevation (docs/viewer.md
// "Remote sources"). Zooms and bounds come from the TileJSON that named the
// template, or from --source-zooms.
#pragma once

#include <array>
#include <memory>
#include <string>

#include "data/raster_tile_fetcher.hpp"
#include "data/tile_requests.hpp"
#include "net/http_client.hpp"

namespace globe::viewer {

class XyzFetcher final : public RasterTileFetcher {
 public:
  // Throws InputError naming the template when it lacks {z}, {x} or {y}/{-y}.
  XyzFetcher(std::string url_template, net::HttpClient& client, int min_zoom, int max_zoom,
             std::array<double, 4> bounds = {-180, -85.0511287798, 180, 85.0511287798});

  std::optional<std::vector<uint8_t>> fetch(tileformat::TileId id) override;
  void prefetch(std::span<const tileformat::TileId> ids) override;
  int min_zoom() const override { return min_zoom_; }
  int max_zoom() const override { return max_zoom_; }
  std::array<double, 4> bounds() const override { return bounds_; }
  const std::string& name() const override { return template_; }

  std::string url(tileformat::TileId id) const;

 private:
  std::string template_;
  int min_zoom_, max_zoom_;
  std::array<double, 4> bounds_;
  std::unique_ptr<TileRequests> requests_;
};

}  // namespace globe::viewer
