// Pass 3 of every vector build (lines, areas): the tiles the sorter gives back
// in key order are encoded in parallel batches and put into the package in
// that order, so output is identical for any thread count; a resumed
// package's tiles, which come first in key order, are skipped.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "kit/progress.hpp"
#include "tileformat/package.hpp"
#include "tiles/tile_sorter.hpp"

namespace globe {

// One encoded tile and two counts its kind reports (segments and points,
// polygons and vertices).
struct EncodedTile {
  std::vector<uint8_t> blob;
  uint64_t first = 0, second = 0;
};

// encode: a tile's records into its blob (on worker threads); written: after
// the blob is in `writer` (on the caller's thread, in key order).
void encode_sorted_tiles(
    TileSorter& sorter, int threads, tileformat::PackageWriter& writer, Progress& progress,
    const std::function<EncodedTile(const TileGroup&)>& encode,
    const std::function<void(tileformat::TileId, const EncodedTile&)>& written);

}  // namespace globe
