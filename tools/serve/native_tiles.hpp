// A package's own tiles and metadata, as stored, for globe-view's remote
// sources (docs/viewer.md "Remote sources"): /NAME/{z}/{x}/{y}.globe answers
// a tile's blob byte for byte, and every TileJSON gets a "globe" member with
// the package's metadata and that URL template, so that a viewer streaming
// from the server decodes the same bytes as one reading the file. A SQLite
// connection of its own, used under its own lock: the kind's service keeps
// its connection and locking to itself.
#pragma once

#include <cstdint>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "tileformat/package.hpp"

namespace globe::serve {

class NativeTiles {
 public:
  explicit NativeTiles(const std::string& path);  // throws PackageError

  std::optional<std::vector<uint8_t>> tile(tileformat::TileId id);
  // `"globe":{"tiles":["BASE/{z}/{x}/{y}.globe"],"zooms":[[Z,MINX,MAXX,MINY,MAXY],
  // ...],"metadata":{KEY:VALUE,...}}`: the member globe-view reads from the
  // TileJSON: the tiles' URLs, each zoom's range of tiles (XYZ rows; where
  // the viewer asks for tiles at all), the metadata (every value a string,
  // as stored).
  std::string tilejson_member(const std::string& base) const;

 private:
  std::mutex mutex_;
  tileformat::PackageReader reader_;
  std::string zooms_;  // the "zooms" array, read once
};

// `tilejson` (a TileJSON object's text) with `member` added as its last member.
std::string with_member(std::string tilejson, const std::string& member);

}  // namespace globe::serve
