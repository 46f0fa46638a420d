// Packages streamed from a server (see remote_reader.hpp).
#include "data/remote_reader.hpp"

#include <algorithm>
#include <stdexcept>

#include "net/url.hpp"
#include "runtime/errors.hpp"
#include "tileformat/error.hpp"
#include "tileformat/json.hpp"

namespace globe::viewer {
namespace {

using tileformat::TileId;

}  // namespace

namespace {

tileformat::JsonValue read_tilejson(const std::string& url, net::HttpClient& client) {
  net::Request req;
  req.url = url;
  req.accept_types = {"application/json"};
  const net::Response r = client.get_blocking(std::move(req));
  if (r.outcome != net::Outcome::kOk)
    throw InputError(url + ": cannot read the TileJSON: " +
                     (r.error.empty() ? std::string(net::to_string(r.outcome)) : r.error));
  try {
    return tileformat::JsonValue::parse(
        std::string_view(reinterpret_cast<const char*>(r.body.data()), r.body.size()));
  } catch (const tileformat::JsonError& e) {
    throw InputError(url + ": not a TileJSON: " + e.what());
  }
}

}  // namespace

RemoteReader::RemoteReader(const std::string& url, net::HttpClient& client)
    : RemoteReader(url, read_tilejson(url, client), client) {}

RemoteReader::RemoteReader(const std::string& url, const tileformat::JsonValue& doc,
                           net::HttpClient& client)
    : url_(url),
      requests_(std::make_unique<TileRequests>(
          client,
          std::vector<std::string>{"application/vnd.globe.tile", "application/octet-stream"})) {
  const tileformat::JsonValue* globe = doc.find("globe");
  if (!globe || !globe->is_object())
    throw InputError(url +
                     ": a TileJSON without a \"globe\" member; globe-view streams what "
                     "globe-serve publishes (HOST/NAME.json) and XYZ image templates "
                     "(…/{z}/{x}/{y}.png)");
  const tileformat::JsonValue* tiles = globe->find("tiles");
  const tileformat::JsonValue* meta = globe->find("metadata");
  const tileformat::JsonValue* zooms = globe->find("zooms");
  if (!tiles || !tiles->is_array() || tiles->array().empty() || !tiles->array()[0].is_string() ||
      !meta || !meta->is_object() || !zooms || !zooms->is_array())
    throw InputError(url + ": the TileJSON's \"globe\" member lacks tiles, zooms or metadata");
  template_ = net::resolve_url(url, tiles->array()[0].string());
  for (const auto& [k, v] : meta->members())
    if (v.is_string()) metadata_[k] = v.string();
  for (const tileformat::JsonValue& z : zooms->array()) {
    if (!z.is_array() || z.array().size() != 5) continue;
    const auto n = [&](int i) {
      return z.array()[size_t(i)].is_number() ? z.array()[size_t(i)].number() : -1;
    };
    if (n(0) < 0 || n(0) > tileformat::kMaxZoom || n(1) < 0 || n(2) < n(1) || n(3) < 0 ||
        n(4) < n(3))
      continue;
    zooms_[int(n(0))] = {uint32_t(n(1)), uint32_t(n(2)), uint32_t(n(3)), uint32_t(n(4))};
  }
}

std::string RemoteReader::tile_url(TileId id) const {
  std::string u = net::fill_placeholder(template_, "{z}", std::to_string(id.z));
  u = net::fill_placeholder(u, "{x}", std::to_string(id.x));
  return net::fill_placeholder(u, "{y}", std::to_string(id.y));
}

void RemoteReader::prefetch(std::span<const TileId> ids) {
  for (const TileId& id : ids)
    requests_->prefetch(id, tile_url(id));
}

void RemoteReader::forget(std::span<const TileId> ids) {
  for (const TileId& id : ids)
    requests_->forget(id);
}

std::optional<std::vector<uint8_t>> RemoteReader::tile(TileId id) {
  return requests_->take(id, tile_url(id));
}

bool RemoteReader::has_tile(TileId id) {
  const auto z = zooms_.find(id.z);
  if (z == zooms_.end() || id.x < z->second.min_x || id.x > z->second.max_x ||
      id.y < z->second.min_y || id.y > z->second.max_y)
    return false;
  return !requests_->absent(id);
}

std::vector<TileId> RemoteReader::tile_ids(int zoom) {
  std::vector<TileId> out;
  const auto z = zooms_.find(zoom);
  if (z == zooms_.end()) return out;
  const Range& r = z->second;
  const uint64_t w = uint64_t(r.max_x) - r.min_x + 1, h = uint64_t(r.max_y) - r.min_y + 1;
  const uint64_t stride = std::max<uint64_t>(1, (w * h + 65535) / 65536);
  for (uint64_t i = 0; i < w * h; i += stride)
    out.push_back({zoom, uint32_t(r.min_x + i % w), uint32_t(r.min_y + i / w)});
  std::sort(out.begin(), out.end(),
            [](const TileId& a, const TileId& b) { return a.y != b.y ? a.y < b.y : a.x < b.x; });
  return out;
}

}  // namespace globe::viewer
