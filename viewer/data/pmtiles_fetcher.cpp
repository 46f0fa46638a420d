// PMTiles over HTTP ranges (see pmtiles_fetcher.hpp).
#include "data/pmtiles_fetcher.hpp"

#include <zlib.h>

#include "runtime/errors.hpp"
#include "tileformat/error.hpp"

namespace globe::viewer {
namespace pm = tileformat::pmtiles;

PmtilesFetcher::PmtilesFetcher(std::string url, net::HttpClient& client)
    : url_(std::move(url)),
      client_(client),
      requests_(std::make_unique<TileRequests>(
          client, std::vector<std::string>{"application/", "image/", "binary/"})) {
  std::vector<uint8_t> first;
  try {
    first = read_range(0, 16384, "header");
    header_ = pm::decode_header(first);
  } catch (const pm::PmtilesError& e) {
    throw InputError(url_ + ": " + e.what());
  } catch (const tileformat::PackageError& e) {
    throw InputError(e.what());
  }
  using TT = pm::TileType;
  if (header_.info.tile_type == TT::kMvt)
    throw InputError(url_ +
                     ": vector tiles (MVT); globe-view draws a line, point or area package: "
                     "serve it with globe-serve and open HOST/NAME.json");
  if (header_.info.tile_type != TT::kPng && header_.info.tile_type != TT::kJpeg &&
      header_.info.tile_type != TT::kWebp)
    throw InputError(url_ + ": tiles of a type globe-view does not decode (PNG, JPEG, WebP only)");
  try {
    std::vector<uint8_t> root =
        header_.root_offset + header_.root_length <= first.size()
            ? std::vector<uint8_t>(first.begin() + long(header_.root_offset),
                                   first.begin() + long(header_.root_offset + header_.root_length))
            : read_range(header_.root_offset, header_.root_length, "root directory");
    root_ = pm::decode_directory(
        uncompress(std::move(root), header_.internal_compression, "root directory"));
  } catch (const pm::PmtilesError& e) {
    throw InputError(url_ + ": " + e.what());
  } catch (const tileformat::PackageError& e) {
    throw InputError(e.what());
  }
}

std::array<double, 4> PmtilesFetcher::bounds() const {
  return {header_.info.min_lon, header_.info.min_lat, header_.info.max_lon, header_.info.max_lat};
}

std::vector<uint8_t> PmtilesFetcher::read_range(uint64_t offset, uint64_t length,
                                                const std::string& what) {
  net::Request req;
  req.url = url_;
  req.range = "bytes=" + std::to_string(offset) + "-" + std::to_string(offset + length - 1);
  net::Response r = client_.get_blocking(std::move(req));
  if (r.outcome != net::Outcome::kOk)
    throw tileformat::PackageError(url_ + ": cannot read its " + what + ": " +
                                   (r.error.empty() ? net::to_string(r.outcome) : r.error));
  return std::move(r.body);
}

std::vector<uint8_t> PmtilesFetcher::uncompress(std::vector<uint8_t> bytes, pm::Compression c,
                                                const std::string& what) const {
  if (c == pm::Compression::kNone || c == pm::Compression::kUnknown) return bytes;
  if (c != pm::Compression::kGzip)
    throw tileformat::PackageError(url_ + ": " + what +
                                   " compressed with brotli or zstd, which globe-view does not "
                                   "read (gzip or none)");
  z_stream z{};
  if (inflateInit2(&z, 16 + MAX_WBITS) != Z_OK)
    throw tileformat::PackageError(url_ + ": " + what + ": zlib failed to start");
  std::vector<uint8_t> out(bytes.size() * 4 + 1024);
  z.next_in = bytes.data();
  z.avail_in = uInt(bytes.size());
  int rc = Z_OK;
  while (rc == Z_OK) {
    if (z.total_out == out.size()) {
      if (out.size() > (size_t{256} << 20)) break;
      out.resize(out.size() * 2);
    }
    z.next_out = out.data() + z.total_out;
    z.avail_out = uInt(out.size() - z.total_out);
    rc = inflate(&z, Z_NO_FLUSH);
  }
  const size_t n = z.total_out;
  inflateEnd(&z);
  if (rc != Z_STREAM_END) throw tileformat::PackageError(url_ + ": " + what + ": not valid gzip");
  out.resize(n);
  return out;
}

std::optional<pm::Entry> PmtilesFetcher::entry_of(uint64_t tile_id, bool may_wait) {
  const std::vector<pm::Entry>* dir = &root_;
  for (int depth = 0; depth < 4; ++depth) {
    const pm::Entry* e = pm::find_entry(*dir, tile_id);
    if (!e) return std::nullopt;
    if (e->run_length > 0) return *e;
    std::unique_lock lock(mutex_);
    auto it = leaves_.find(e->offset);
    if (it == leaves_.end()) {
      if (!may_wait) return std::nullopt;
      const uint64_t offset = e->offset, length = e->length;
      lock.unlock();
      std::vector<pm::Entry> leaf;
      try {
        leaf = pm::decode_directory(
            uncompress(read_range(header_.leaf_offset + offset, length, "leaf directory"),
                       header_.internal_compression, "leaf directory"));
      } catch (const pm::PmtilesError& err) {
        throw tileformat::PackageError(url_ + ": " + err.what());
      }
      lock.lock();
      it = leaves_.try_emplace(offset, std::move(leaf)).first;
    }
    dir = &it->second;  // std::map: stable while the fetcher lives
  }
  throw tileformat::PackageError(url_ + ": leaf directories nested deeper than 3");
}

std::optional<std::vector<uint8_t>> PmtilesFetcher::fetch(tileformat::TileId id) {
  if (id.z < min_zoom() || id.z > max_zoom()) return std::nullopt;
  const std::optional<pm::Entry> e = entry_of(pm::tile_id(id.z, id.x, id.y), true);
  if (!e) return std::nullopt;
  const uint64_t at = header_.data_offset + e->offset;
  auto bytes = requests_->take(
      id, url_, "bytes=" + std::to_string(at) + "-" + std::to_string(at + e->length - 1));
  if (!bytes) return std::nullopt;
  return uncompress(std::move(*bytes), header_.info.tile_compression, "tile " + id.str());
}

void PmtilesFetcher::prefetch(std::span<const tileformat::TileId> ids) {
  for (const tileformat::TileId& id : ids) {
    if (id.z < min_zoom() || id.z > max_zoom()) continue;
    const std::optional<pm::Entry> e = entry_of(pm::tile_id(id.z, id.x, id.y), false);
    if (!e) continue;
    const uint64_t at = header_.data_offset + e->offset;
    requests_->prefetch(id, url_,
                        "bytes=" + std::to_string(at) + "-" + std::to_string(at + e->length - 1));
  }
}

std::string PmtilesFetcher::metadata_json() {
  if (!header_.metadata_length) return "{}";
  const std::vector<uint8_t> m =
      uncompress(read_range(header_.metadata_offset, header_.metadata_length, "metadata"),
                 header_.internal_compression, "metadata");
  return std::string(m.begin(), m.end());
}

}  // namespace globe::viewer
