// Raster tiles from an XYZ URL template (see xyz_fetcher.hpp).
#include "data/xyz_fetcher.hpp"

#include "net/url.hpp"
#include "runtime/errors.hpp"

namespace globe::viewer {

XyzFetcher::XyzFetcher(std::string url_template, net::HttpClient& client, int min_zoom,
                       int max_zoom, std::array<double, 4> bounds)
    : template_(std::move(url_template)),
      min_zoom_(min_zoom),
      max_zoom_(max_zoom),
      bounds_(bounds),
      requests_(std::make_unique<TileRequests>(
          client, std::vector<std::string>{"image/", "application/octet-stream"})) {
  if (template_.find("{z}") == std::string::npos || template_.find("{x}") == std::string::npos ||
      (template_.find("{y}") == std::string::npos && template_.find("{-y}") == std::string::npos))
    throw InputError(template_ + ": an XYZ template needs {z}, {x} and {y} (or {-y})");
}

std::string XyzFetcher::url(tileformat::TileId id) const {
  std::string u = net::fill_placeholder(template_, "{z}", std::to_string(id.z));
  u = net::fill_placeholder(u, "{x}", std::to_string(id.x));
  u = net::fill_placeholder(u, "{-y}", std::to_string((uint64_t{1} << id.z) - 1 - id.y));
  return net::fill_placeholder(u, "{y}", std::to_string(id.y));
}

std::optional<std::vector<uint8_t>> XyzFetcher::fetch(tileformat::TileId id) {
  if (id.z < min_zoom_ || id.z > max_zoom_ || id.x >= (uint64_t{1} << id.z) ||
      id.y >= (uint64_t{1} << id.z))
    return std::nullopt;
  return requests_->take(id, url(id));
}

void XyzFetcher::prefetch(std::span<const tileformat::TileId> ids) {
  for (const tileformat::TileId& id : ids)
    if (id.z >= min_zoom_ && id.z <= max_zoom_ && id.x < (uint64_t{1} << id.z) &&
        id.y < (uint64_t{1} << id.z))
      requests_->prefetch(id, url(id));
}

}  // namespace globe::viewer
