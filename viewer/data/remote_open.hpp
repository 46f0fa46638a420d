// Which reader a URL on globe-view's command line becomes (docs/viewer.md
// "Remote sources"):
//   HOST/NAME.json with a "globe" member (globe-serve)  -> RemoteReader
//   another TileJSON of raster tiles                    -> imagery, or elevation
//                                                          with --dem-encoding or
//                                                          its "encoding"
//   …/{z}/{x}/{y}.png|jpg|webp ({-y}: TMS rows)         -> imagery, or elevation
//                                                          with --dem-encoding
//   …/FILE.pmtiles (HTTP ranges)                        -> imagery, or elevation
//                                                          with --dem-encoding
//   …/layer.json (quantized-mesh, CesiumJS terrain)     -> elevation
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <utility>

#include "net/http_client.hpp"
#include "tileformat/tile_reader.hpp"

namespace globe::viewer {

struct RemoteOptions {
  std::string dem_encoding;                         // "", "terrarium" or "terrain-rgb"
  std::optional<std::pair<int, int>> source_zooms;  // --source-zooms for XYZ templates
};

// Throws InputError naming the URL: unreachable, or not one of the above.
std::unique_ptr<tileformat::TileReader> open_remote(const std::string& url, net::HttpClient& client,
                                                    const RemoteOptions& options);

}  // namespace globe::viewer
