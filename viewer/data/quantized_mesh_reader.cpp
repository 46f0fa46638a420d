// A CesiumJS quantized-mesh tileset as terrain blocks (see
// quantized_mesh_reader.hpp). Reads through the HttpClient only; decodes
// with quantized_mesh_decode, samples with mesh_grid, makes the blobs with
// BlockSynthesizer; writes nothing but its caches.
#include "data/quantized_mesh_reader.hpp"
#include "data/web_mercator.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <numbers>
#include <stdexcept>

#include "data/mesh_grid.hpp"
#include "net/url.hpp"
#include "runtime/errors.hpp"
#include "tileformat/error.hpp"
#include "tileformat/json.hpp"
#include "tileformat/metadata.hpp"
#include "tileformat/package_kinds.hpp"

namespace globe::viewer {
namespace {

using tileformat::JsonValue;
using tileformat::TileId;

// More requests answered and never read than this, and the oldest answers go.
constexpr size_t kMaxPending = 1024;

uint64_t key(TileId id) {
  return (uint64_t(id.z) << 58) | (uint64_t(id.x) << 29) | id.y;
}

std::string outcome_text(const net::Response& r) {
  return r.error.empty() ? std::string(net::to_string(r.outcome)) : r.error;
}

}  // namespace

QuantizedMeshReader::QuantizedMeshReader(const std::string& url, net::HttpClient& client)
    : url_(url), client_(client), shared_(std::make_shared<Shared>()) {
  // layer.json: any content type (static hosts label it variously); gzip
  // without Content-Encoding inflated here.
  net::Request req;
  req.url = url;
  const net::Response r = client_.get_blocking(std::move(req));
  if (r.outcome != net::Outcome::kOk)
    throw InputError(url + ": cannot read the layer.json: " + outcome_text(r));
  JsonValue doc;
  try {
    const std::vector<uint8_t> text = gunzip_if_gzipped(r.body, size_t{64} << 20);
    doc =
        JsonValue::parse(std::string_view(reinterpret_cast<const char*>(text.data()), text.size()));
  } catch (const std::exception& e) {
    throw InputError(url + ": not a layer.json: " + e.what());
  }
  if (!doc.is_object()) throw InputError(url + ": not a layer.json: not a JSON object");
  auto string_member = [&](const char* name, const std::string& fallback) {
    const JsonValue* v = doc.find(name);
    return v && v->is_string() ? v->string() : fallback;
  };
  const std::string format = string_member("format", "");
  if (!format.starts_with("quantized-mesh-1."))
    throw InputError(url + ": format \"" + format +
                     "\"; globe-view reads CesiumJS terrain in quantized-mesh-1.x");
  const std::string scheme = string_member("scheme", "tms");
  if (scheme != "tms")
    throw InputError(url + ": scheme \"" + scheme + "\"; quantized-mesh tilesets are \"tms\"");
  const std::string projection = string_member("projection", "EPSG:4326");
  if (projection == "EPSG:4326")
    tiling_ = tileformat::Tiling::geodetic();
  else if (projection == "EPSG:3857")
    tiling_ = tileformat::Tiling::webmercator();
  else
    throw InputError(url + ": projection \"" + projection +
                     "\"; quantized-mesh tilesets are EPSG:4326 or EPSG:3857");

  // Tile URLs: relative to the layer.json (without its query, which every
  // tile request carries on, as CesiumJS does: an access token, say).
  std::string base = url.substr(0, url.find('#'));
  if (const size_t q = base.find('?'); q != std::string::npos) {
    query_ = base.substr(q + 1);
    base.resize(q);
  }
  const std::string version = string_member("version", "1.0.0");
  const JsonValue* tiles = doc.find("tiles");
  if (tiles && tiles->is_array())
    for (const JsonValue& t : tiles->array())
      if (t.is_string() && !t.string().empty())
        templates_.push_back(
            net::fill_placeholder(net::resolve_url(base, t.string()), "{version}", version));
  if (templates_.empty()) throw InputError(url + ": the layer.json has no tiles URL template");

  // Zooms and availability.
  auto integer = [&](const JsonValue* v, const std::string& what) -> int64_t {
    if (!v || !v->is_number() || v->number() < 0 || v->number() > 4294967295.0 ||
        v->number() != std::floor(v->number()))
      throw InputError(url + ": " + what + " is not a non-negative integer");
    return int64_t(v->number());
  };
  const bool metadata_availability = doc.find("metadataAvailability") != nullptr;
  if (const JsonValue* available = doc.find("available")) {
    if (!available->is_array()) throw InputError(url + ": \"available\" is not an array");
    for (const JsonValue& level : available->array()) {
      const int z = int(available_.size());
      if (z > tileformat::kMaxZoom) break;
      if (!level.is_array())
        throw InputError(url + ": \"available\" zoom " + std::to_string(z) + " is not an array");
      std::vector<TmsRect>& rects = available_.emplace_back();
      const int64_t last_x = int64_t(tiling_.tiles_x(z)) - 1,
                    last_y = int64_t(tiling_.tiles_y(z)) - 1;
      for (const JsonValue& range : level.array()) {
        const std::string where = "\"available\" zoom " + std::to_string(z);
        if (!range.is_object()) throw InputError(url + ": " + where + " holds a non-object");
        const int64_t x0 = integer(range.find("startX"), where + " startX"),
                      x1 = integer(range.find("endX"), where + " endX"),
                      y0 = integer(range.find("startY"), where + " startY"),
                      y1 = integer(range.find("endY"), where + " endY");
        if (x0 > x1 || y0 > y1 || x0 > last_x || y0 > last_y) continue;  // empty or outside
        rects.push_back({uint32_t(x0), uint32_t(std::min(x1, last_x)), uint32_t(y0),
                         uint32_t(std::min(y1, last_y))});
      }
    }
  }
  min_zoom_ = int(std::min<int64_t>(
      doc.find("minzoom") ? integer(doc.find("minzoom"), "minzoom") : 0, tileformat::kMaxZoom));
  if (const JsonValue* mz = doc.find("maxzoom"))
    max_zoom_ = int(std::min<int64_t>(integer(mz, "maxzoom"), tileformat::kMaxZoom));
  else if (!available_.empty())
    max_zoom_ = int(available_.size()) - 1;
  else
    throw InputError(url + ": the layer.json has neither maxzoom nor available");
  // Without metadataAvailability, what `available` leaves out does not exist.
  if (!available_.empty() && !metadata_availability)
    max_zoom_ = std::min(max_zoom_, int(available_.size()) - 1);
  if (min_zoom_ > max_zoom_)
    throw InputError(url + ": minzoom " + std::to_string(min_zoom_) + " is above maxzoom " +
                     std::to_string(max_zoom_));
  // Bounds (degrees), in the tiling's CRS for the zooms `available` does not list.
  const tileformat::Bounds lim = tiling_.lonlat_limits();
  tileformat::Bounds lonlat = lim;
  if (const JsonValue* b = doc.find("bounds");
      b && b->is_array() && b->array().size() == 4 &&
      std::all_of(b->array().begin(), b->array().end(),
                  [](const JsonValue& v) { return v.is_number() && std::isfinite(v.number()); })) {
    const auto& a = b->array();
    lonlat = {std::clamp(a[0].number(), lim.min_x, lim.max_x),
              std::clamp(a[1].number(), lim.min_y, lim.max_y),
              std::clamp(a[2].number(), lim.min_x, lim.max_x),
              std::clamp(a[3].number(), lim.min_y, lim.max_y)};
    if (!(lonlat.min_x < lonlat.max_x && lonlat.min_y < lonlat.max_y)) lonlat = lim;
  }
  crs_bounds_ = tiling_.scheme == tileformat::Scheme::kWebMercator
                    ? tileformat::Bounds{mercator_x(lonlat.min_x), mercator_y(lonlat.min_y),
                                         mercator_x(lonlat.max_x), mercator_y(lonlat.max_y)}
                    : lonlat;

  const std::string description =
      "CesiumJS quantized-mesh terrain from " + url + ", made into terrain blocks by globe-view";
  if (tiling_.scheme == tileformat::Scheme::kWebMercator) {
    SynthesizedTerrain t;
    t.name = url;
    t.description = description;
    t.block_size = kBlockSize;
    t.lattice = kLattice;
    t.height_step = kHeightStep;
    t.min_zoom = min_zoom_;
    t.max_zoom = max_zoom_;
    t.lonlat = lonlat;
    metadata_ = terrain_metadata_for(t);
  } else {
    // terrain_metadata_for writes web mercator packages only: the same keys
    // for the geodetic tiling.
    tileformat::TerrainMetadata m;
    tileformat::CommonMetadata& c = m.common;
    c.tiling = tiling_;
    c.name = url;
    c.format = tileformat::kMBlockFormat;
    c.type = "baselayer";
    c.description = description;
    c.lonlat = lonlat;
    c.min_zoom = min_zoom_;
    c.max_zoom = max_zoom_;
    c.center_zoom = tiling_.view_zoom(lonlat, min_zoom_, max_zoom_);
    c.generator = "globe-view";
    c.inputs = {{url, 0}};
    m.resampling = "bilinear";  // heights interpolated in the mesh's triangles
    m.block_size = kBlockSize;
    m.lattice = kLattice;
    m.height_step = kHeightStep;
    m.fill_height = 0;
    metadata_ = tileformat::to_metadata(m);
    metadata_["globe:synthesized"] = "1";  // blocks not nested: the viewer hangs skirts
  }
  blocks_ = std::make_unique<BlockSynthesizer>(
      kBlockSize, kLattice, kHeightStep, [this](TileId id) { return samples(id); }, kCachedBlocks,
      tiling_);
  // Coarser zooms leave out what finer ones show: CesiumJS's geometric
  // error of a quantized-mesh level (its heightmap estimate for 65 samples a
  // tile), which is what producers cut their TINs to; the finest zoom's
  // error is the data's.
  blocks_->set_level_error([max = max_zoom_, roots = tiling_.roots_x](int z) {
    return z >= max ? 0.0 : cesium_level_error_m(z, 65, roots);
  });
}

QuantizedMeshReader::~QuantizedMeshReader() {
  std::lock_guard lock(shared_->mutex);
  for (const auto& [k, p] : pending_)
    if (!p->done) client_.cancel(p->request);
}

std::string QuantizedMeshReader::tile_url(TileId id) const {
  const uint32_t tms_y = uint32_t(tiling_.tiles_y(id.z) - 1 - id.y);
  // CesiumJS spreads tiles over several templates (hosts) by x + y + level.
  const std::string& t = templates_[(uint64_t(id.x) + tms_y + uint64_t(id.z)) % templates_.size()];
  std::string u = net::fill_placeholder(t, "{z}", std::to_string(id.z));
  u = net::fill_placeholder(u, "{x}", std::to_string(id.x));
  u = net::fill_placeholder(u, "{y}", std::to_string(tms_y));
  if (!query_.empty()) u += (u.find('?') == std::string::npos ? "?" : "&") + query_;
  return u;
}

bool QuantizedMeshReader::listed(TileId id) const {
  if (id.z < min_zoom_ || id.z > max_zoom_ || !tiling_.contains(id)) return false;
  if (size_t(id.z) < available_.size()) {
    const uint32_t tms_y = uint32_t(tiling_.tiles_y(id.z) - 1 - id.y);
    return std::any_of(available_[size_t(id.z)].begin(), available_[size_t(id.z)].end(),
                       [&](const TmsRect& r) {
                         return id.x >= r.x0 && id.x <= r.x1 && tms_y >= r.y0 && tms_y <= r.y1;
                       });
  }
  const tileformat::TileRange r = tiling_.tiles_covering(crs_bounds_, id.z);
  return !r.empty() && id.x >= r.min_x && id.x <= r.max_x && id.y >= r.min_y && id.y <= r.max_y;
}

bool QuantizedMeshReader::has_tile(TileId id) {
  if (!listed(id)) return false;
  std::lock_guard lock(shared_->mutex);
  return !absent_.count(id);
}

std::optional<TileId> QuantizedMeshReader::neighbour(TileId id, int dx, int dy) const {
  const int64_t nx = int64_t(tiling_.tiles_x(id.z)), ny = int64_t(tiling_.tiles_y(id.z));
  const int64_t y = int64_t{id.y} + dy;
  if (y < 0 || y >= ny) return std::nullopt;                // beyond a pole
  const int64_t x = ((int64_t{id.x} + dx) % nx + nx) % nx;  // across the antimeridian
  return TileId{id.z, uint32_t(x), uint32_t(y)};
}

std::vector<TileId> QuantizedMeshReader::tile_ids(int zoom) {
  std::vector<TileId> out;
  if (zoom < min_zoom_ || zoom > max_zoom_) return out;
  const uint64_t rows = tiling_.tiles_y(zoom);
  if (size_t(zoom) < available_.size()) {
    const std::vector<TmsRect>& rects = available_[size_t(zoom)];
    uint64_t total = 0;
    for (const TmsRect& r : rects)
      total += (uint64_t{r.x1} - r.x0 + 1) * (uint64_t{r.y1} - r.y0 + 1);
    const uint64_t stride = std::max<uint64_t>(1, (total + 65535) / 65536);
    uint64_t at = 0;  // index over the rectangles' tiles, one after another
    for (const TmsRect& r : rects) {
      const uint64_t w = uint64_t{r.x1} - r.x0 + 1, n = w * (uint64_t{r.y1} - r.y0 + 1);
      for (uint64_t i = (stride - at % stride) % stride; i < n; i += stride)
        out.push_back({zoom, uint32_t(r.x0 + i % w), uint32_t(rows - 1 - (r.y0 + i / w))});
      at += n;
    }
  } else {
    const tileformat::TileRange r = tiling_.tiles_covering(crs_bounds_, zoom);
    if (r.empty()) return out;
    const uint64_t w = uint64_t{r.max_x} - r.min_x + 1, h = uint64_t{r.max_y} - r.min_y + 1;
    const uint64_t stride = std::max<uint64_t>(1, (w * h + 65535) / 65536);
    for (uint64_t i = 0; i < w * h; i += stride)
      out.push_back({zoom, uint32_t(r.min_x + i % w), uint32_t(r.min_y + i / w)});
  }
  std::sort(out.begin(), out.end(),
            [](const TileId& a, const TileId& b) { return a.y != b.y ? a.y < b.y : a.x < b.x; });
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

// Under shared_->mutex.
std::shared_ptr<QuantizedMeshReader::Pending> QuantizedMeshReader::ask(TileId id, double priority) {
  auto [it, fresh] = pending_.try_emplace(key(id));
  if (!fresh) return it->second;
  if (pending_.size() > kMaxPending)  // answers nobody read: let them go
    std::erase_if(pending_, [&](const auto& e) { return e.second->done && e.first != key(id); });
  auto p = std::make_shared<Pending>();
  it = pending_.find(key(id));
  it->second = p;
  net::Request req;
  req.url = tile_url(id);
  req.priority = priority;
  req.accept_types = {"application/vnd.quantized-mesh", "application/octet-stream"};
  // Decoded on the client's thread: a broken tile is kBroken and never
  // cached, and the mesh is not decoded twice.
  std::shared_ptr<Shared> shared = shared_;
  req.validate = [p, shared](const std::vector<uint8_t>& body, const std::string&) {
    try {
      auto mesh = std::make_shared<const QuantizedMesh>(decode_quantized_mesh(body));
      std::lock_guard lock(shared->mutex);
      p->mesh = std::move(mesh);
      return std::string();
    } catch (const tileformat::FormatError& e) {
      return std::string(e.what());
    }
  };
  p->request = client_.get(std::move(req), [p, shared](net::Response r) {
    {
      std::lock_guard lock(shared->mutex);
      p->response = std::move(r);
      p->done = true;
    }
    shared->answered.notify_all();
  });
  return p;
}

void QuantizedMeshReader::prefetch(std::span<const TileId> ids) {
  std::vector<TileId> wanted;
  for (const TileId& id : ids)
    if (listed(id)) wanted.push_back(id);
  std::lock_guard lock(shared_->mutex);
  for (const TileId& id : wanted)
    if (!absent_.count(id) && !tiles_.contains(id)) ask(id, next_priority_ -= 1);
}

void QuantizedMeshReader::forget(std::span<const TileId> ids) {
  std::lock_guard lock(shared_->mutex);
  for (const TileId& id : ids) {
    const auto it = pending_.find(key(id));
    if (it == pending_.end()) continue;
    if (!it->second->done) client_.cancel(it->second->request);
    pending_.erase(it);  // whoever waits on it holds it, and asks again if cancelled
  }
}

std::shared_ptr<const QuantizedMeshReader::Sampled> QuantizedMeshReader::fetch_and_sample(
    TileId id) {
  auto s = std::make_shared<Sampled>();
  if (!has_tile(id)) return s;
  std::shared_ptr<Pending> p;
  std::shared_ptr<const QuantizedMesh> mesh;
  // A request cancelled under us (forget() of a tile that is also another
  // block's neighbour) is asked once more.
  for (int attempt = 0; attempt < 2; ++attempt) {
    std::unique_lock lock(shared_->mutex);
    p = ask(id, next_priority_ -= 1);
    shared_->answered.wait(lock, [&] { return p->done; });
    if (const auto it = pending_.find(key(id)); it != pending_.end() && it->second == p)
      pending_.erase(it);
    if (p->response.outcome == net::Outcome::kCancelled) continue;
    if (p->response.outcome == net::Outcome::kNoContent) absent_.insert(id);
    mesh = p->mesh;
    break;
  }
  const net::Response& r = p->response;
  if (r.outcome == net::Outcome::kNoContent) return s;
  if (r.outcome != net::Outcome::kOk)
    throw tileformat::PackageError(tile_url(id) + ": " + outcome_text(r));
  if (!mesh) {  // from the client's cache, which does not validate again
    try {
      mesh = std::make_shared<const QuantizedMesh>(decode_quantized_mesh(r.body));
    } catch (const tileformat::FormatError& e) {
      throw tileformat::PackageError(tile_url(id) + ": " + e.what());
    }
  }
  // Web mercator blocks' rows are evenly spaced in mercator y, the tile's v in latitude.
  const std::vector<double> rows = tiling_.scheme == tileformat::Scheme::kWebMercator
                                       ? mercator_row_v(id.z, id.y, kBlockSize)
                                       : std::vector<double>();
  s->h = mesh_grid(*mesh, kBlockSize, rows);
  s->present = true;
  return s;
}

std::shared_ptr<const QuantizedMeshReader::Sampled> QuantizedMeshReader::own(TileId id) {
  return tiles_.get(id, [&] { return fetch_and_sample(id); });
}

std::optional<std::vector<float>> QuantizedMeshReader::samples(TileId id) {
  if (!has_tile(id)) return std::nullopt;
  const std::optional<TileId> east = neighbour(id, 1, 0), south = neighbour(id, 0, 1),
                              south_east = neighbour(id, 1, 1), north_east = neighbour(id, 1, -1);
  {  // the tiles this block reads, asked at once
    std::vector<TileId> wanted{id};
    for (const auto& t : {east, south, south_east})
      if (t) wanted.push_back(*t);
    prefetch(wanted);
  }
  const std::shared_ptr<const Sampled> self = own(id);
  if (!self->present) return std::nullopt;
  auto other = [&](const std::optional<TileId>& t) -> std::shared_ptr<const Sampled> {
    if (!t) return nullptr;
    std::shared_ptr<const Sampled> s = own(*t);
    return s->present ? s : nullptr;
  };
  const std::shared_ptr<const Sampled> e = other(east), s = other(south), se = other(south_east);
  const std::shared_ptr<const Sampled> ne = e ? nullptr : other(north_east);

  // Shared samples from their owners (docs/tileformat.md §2.1; the top of
  // the header): the east tile's first column, the south tile's first row,
  // the corners from the first present of SE, NE, SW, NW around them.
  constexpr size_t n = kBlockSize, last = n - 1;
  const auto at = [](size_t i, size_t j) { return j * n + i; };
  std::vector<float> out = self->h;
  if (e)
    for (size_t j = 1; j < last; ++j)
      out[at(last, j)] = e->h[at(0, j)];
  if (s)
    for (size_t i = 1; i < last; ++i)
      out[at(i, last)] = s->h[at(i, 0)];
  // North-east corner: around it N, NE / this, E.
  if (e)
    out[at(last, 0)] = e->h[at(0, 0)];
  else if (ne)
    out[at(last, 0)] = ne->h[at(0, last)];
  // South-west corner: around it W, this / SW, S.
  if (s) out[at(0, last)] = s->h[at(0, 0)];
  // South-east corner: around it this, E / S, SE.
  if (se)
    out[at(last, last)] = se->h[at(0, 0)];
  else if (e)
    out[at(last, last)] = e->h[at(0, last)];
  else if (s)
    out[at(last, last)] = s->h[at(last, 0)];
  return out;
}

std::optional<std::vector<uint8_t>> QuantizedMeshReader::tile(TileId id) {
  if (!has_tile(id)) return std::nullopt;
  {  // what the block reads: its 3 x 3 neighbourhood, the tiles east and
     // south of that (their edges) and its ancestors, asked at once, this
     // tile first
    std::vector<TileId> wanted{id};
    for (int dy = -1; dy <= 2; ++dy)
      for (int dx = -1; dx <= 2; ++dx)
        if (auto t = neighbour(id, dx, dy); t && *t != id) wanted.push_back(*t);
    for (TileId up = id; up.z > 0;) {  // nested blocks read their ancestors
      up = up.parent();
      wanted.push_back(up);
    }
    prefetch(wanted);
  }
  std::optional<std::vector<uint8_t>> blob = blocks_->blob(id);
  if (!blob) {
    std::lock_guard lock(shared_->mutex);
    absent_.insert(id);
  }
  return blob;
}

}  // namespace globe::viewer
