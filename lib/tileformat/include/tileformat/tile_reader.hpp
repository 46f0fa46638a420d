// TileReader: reading a package's tiles, wherever they are — the SQLite file
// (PackageReader, package.hpp) or a server (the viewer's remote sources,
// viewer/data/remote_reader.hpp). Everything that only reads tiles and
// metadata takes a TileReader; what reads a package's other tables (features,
// labels, shards) needs the file itself: package() says whether there is one.
//
// Thread safety as PackageReader's: tile() from one thread while another
// calls has_tile(); a remote reader allows tile() from several threads.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "tileformat/tile_id.hpp"

namespace tileformat {

class PackageReader;

class TileReader {
 public:
  virtual ~TileReader() = default;

  virtual const std::map<std::string, std::string>& metadata() const = 0;
  std::optional<std::string> meta(const std::string& key) const {
    const auto it = metadata().find(key);
    if (it == metadata().end()) return std::nullopt;
    return it->second;
  }
  // Copy of the tile blob, or nullopt if there is none at `id`. A remote
  // reader waits for the answer and throws PackageError for a tile it could
  // not get (a broken answer, the network gave up).
  virtual std::optional<std::vector<uint8_t>> tile(TileId id) = 0;
  // Whether there is a tile at `id` without reading it (a remote reader: from
  // the source's zooms and bounds, and what it has answered already).
  virtual bool has_tile(TileId id) = 0;
  // The tiles of one zoom, in (y, x) order (a remote reader: those in its bounds).
  virtual std::vector<TileId> tile_ids(int zoom) = 0;
  // The file or URL, for messages.
  virtual const std::string& path() const = 0;
  // These tiles will be read soon, the first most urgent: a remote reader
  // asks for them all at once; a file does nothing.
  virtual void prefetch(std::span<const TileId> ids) { (void)ids; }
  // No longer wanted (the view moved on): a remote reader cancels what it has
  // not fetched yet.
  virtual void forget(std::span<const TileId> ids) { (void)ids; }
  // The package file behind this reader, for its other tables; nullptr for a
  // remote source.
  virtual PackageReader* package() { return nullptr; }
};

}  // namespace tileformat
