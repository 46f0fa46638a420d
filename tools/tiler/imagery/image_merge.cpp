// Image shard merge (see image_merge.hpp).
#include "imagery/image_merge.hpp"

#include <chrono>

#include "kit/package_output.hpp"
#include "raster/staged_package.hpp"
#include "runtime/package_open.hpp"
#include "tileformat/error.hpp"
#include "tileformat/image_tile.hpp"
#include "tileformat/metadata.hpp"

namespace globe {

using tileformat::TileId;

ImageSummary merge_imagery(ShardSet& shards, const BuildOptions& o, Progress& progress) {
  const auto start = std::chrono::steady_clock::now();
  const std::string& first = shards.path(0);
  const tileformat::ImageMetadata meta =
      read_metadata(first, [&] { return tileformat::read_image_metadata(shards.metadata()); });
  const tileformat::ShardMetadata shard = *tileformat::read_shard_metadata(shards.metadata());
  ImagePlan plan;
  plan.tiling = meta.common.tiling;
  plan.min_zoom = shard.min_zoom;
  plan.max_zoom = meta.common.max_zoom;
  plan.colour = meta.colour_bands;
  ImageSettings s;
  static_cast<BuildOptions&>(s) = o;
  s.tile_size = meta.tile_size;
  s.format = meta.format;
  s.quality = meta.quality.value_or(s.quality);
  s.png_level = meta.png_level.value_or(s.png_level);

  ImageSummary sum;
  auto count = [&](std::span<const uint8_t> blob) {
    switch (tileformat::inspect_image_tile(blob).format) {
      case tileformat::ImageFormat::kPng:
        ++sum.png;
        break;
      case tileformat::ImageFormat::kJpeg:
        ++sum.jpeg;
        break;
      case tileformat::ImageFormat::kWebp:
        ++sum.webp;
        break;
    }
  };
  int coarsest = shards.split_zoom();
  std::unique_ptr<tileformat::PackageWriter> writer =
      write_staged_package(o, progress, [&](tileformat::PackageWriter& w, StagingStore& stage) {
        const bool above_done = w.resumed() && stage.checkpoint().has_value();
        // Zooms from the finest to the split: every shard's tiles, (y, x) order.
        for (int z = plan.max_zoom; z >= shards.split_zoom(); --z) {
          const std::vector<TileId> tiles = shards.tiles(z);
          const size_t done = w.resumed() ? w.tiles_at_zoom(z) : 0;
          progress.begin("z" + std::to_string(z) + " merge", tiles.size());
          for (size_t i = 0; i < tiles.size(); ++i) {
            if (i > 0 && tiles[i] == tiles[i - 1])
              throw InputError("tile " + tiles[i].str() + " is in two shards; the shards overlap");
            const int owner = shards.owner(tiles[i]);
            if (owner < 0)
              throw InputError(
                  "tile " + tiles[i].str() +
                  " lies in no shard's subtrees; the shards do not come from one build");
            auto blob = shards.reader(owner).tile(tiles[i]);
            if (!blob)
              throw InputError(shards.path(owner) + ": tile " + tiles[i].str() +
                               " is listed but unreadable");
            try {
              count(*blob);
            } catch (const tileformat::FormatError& e) {
              throw InputError(shards.path(owner) + ": tile " + tiles[i].str() + ": " + e.what());
            }
            if (i >= done) w.put_tile(tiles[i], *blob);
            progress.advance();
          }
          progress.end();
          w.checkpoint();
        }
        if (shards.split_zoom() > plan.min_zoom) {
          if (!above_done) {  // the split zoom's pixels, as the builder stages them
            const int z = shards.split_zoom();
            for (const TileId& id : shards.tiles(z)) {
              const int owner = shards.owner(id);
              auto pixels = shards.table(owner).get(kShardPixels, id);
              if (!pixels)
                throw InputError(
                    shards.path(owner) + ": tile " + id.str() +
                    " (split zoom) has no pixels in the shard table; rebuild the shard");
              stage.put(Stage::kRaw, id, *pixels);
            }
            stage.commit({z - 1, 0, 0, 0});
          }
          const ImageLevels above =
              build_imagery_levels(plan, s, w, stage, shards.split_zoom() - 1, progress);
          coarsest = above.coarsest;
          sum.png += above.formats.png;
          sum.jpeg += above.formats.jpeg;
          sum.webp += above.formats.webp;
        }
      });
  if (writer->tiles_written() == 0)
    throw InputError("the shards hold no tiles; nothing written to " + o.output);
  tileformat::MetadataMap m = shards.merged_metadata(o.output, coarsest, o.command_line);
  if (sum.png == 0) m.erase("globe:png_level");  // as the whole build: only with PNG tiles
  writer->set_metadata(m);
  commit_package(*writer, o.output, start, sum);
  return sum;
}

}  // namespace globe
