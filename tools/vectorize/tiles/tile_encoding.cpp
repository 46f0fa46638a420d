// Parallel, ordered tile encoding (see tile_encoding.hpp).
#include "tiles/tile_encoding.hpp"

#include "kit/parallel_batches.hpp"
#include "tiles/tile_cutter.hpp"

namespace globe {

void encode_sorted_tiles(
    TileSorter& sorter, int threads, tileformat::PackageWriter& writer, Progress& progress,
    const std::function<EncodedTile(const TileGroup&)>& encode,
    const std::function<void(tileformat::TileId, const EncodedTile&)>& written) {
  progress.begin("encode tiles", sorter.records());
  uint64_t skip = writer.resumed() ? writer.tiles_written() : 0;
  std::vector<TileGroup> groups;
  for (bool more = true; more;) {
    groups.clear();
    size_t bytes = 0;
    while (groups.size() < size_t(64 * threads) && bytes < (16u << 20)) {
      TileGroup g;
      if (!sorter.next_group(g)) {
        more = false;
        break;
      }
      if (skip > 0) {
        --skip;
        progress.advance(g.records.size());
        continue;
      }
      bytes += g.bytes.size() + g.records.size() * sizeof(TileRecord);
      groups.push_back(std::move(g));
    }
    parallel_batches<NoInputs, EncodedTile>(
        groups.size(), threads, groups.size(), [](size_t, size_t) { return NoInputs{}; },
        [&](size_t i, int, const NoInputs&) { return encode(groups[i]); },
        [&](size_t i, EncodedTile&& e) {
          const tileformat::TileId id = key_tile(groups[i].key);
          writer.put_tile(id, e.blob);
          written(id, e);
          progress.advance(groups[i].records.size());
        },
        [](size_t) {});
  }
  progress.end();
}

}  // namespace globe
