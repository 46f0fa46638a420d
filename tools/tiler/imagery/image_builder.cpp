// Image package builder (see image_builder.hpp).
#include "imagery/image_builder.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <thread>

#include "geo/image_codec.hpp"
#include "imagery/image_pyramid.hpp"
#include "imagery/image_warper.hpp"
#include "kit/package_output.hpp"
#include "kit/parallel_batches.hpp"
#include "kit/shard_plan.hpp"
#include "raster/data_probe.hpp"
#include "raster/raster_metadata.hpp"
#include "raster/raster_stages.hpp"
#include "raster/staged_package.hpp"
#include "raster/tile_groups.hpp"
#include "runtime/errors.hpp"
#include "tileformat/error.hpp"
#include "tileformat/package.hpp"
#include "tileformat/shard_table.hpp"
#include "tileformat/zstd_codec.hpp"

namespace globe {
namespace {

using tileformat::TileId;

constexpr int kStageZstdLevel = 1;

struct TileOut {
  TileId id;
  std::vector<uint8_t> stage;  // zstd pixels for the next coarser zoom (empty: not needed)
  std::vector<uint8_t> blob;   // encoded tile
};

class Builder {
 public:
  Builder(const ImagePlan& plan, const ImageSettings& s, Progress& progress,
          const ShardPlan* shard = nullptr)
      : plan_(plan), s_(s), progress_(progress), threads_(s.worker_threads()), shard_(shard) {}

  ImageSummary run() {
    const auto start = std::chrono::steady_clock::now();
    std::unique_ptr<tileformat::PackageWriter> writer =
        write_staged_package(s_, progress_, [&](tileformat::PackageWriter& w, StagingStore& stage) {
          with_shard_table(w, shard_, [&](tileformat::ShardTableWriter* parts) {
            parts_ = parts;
            levels(w, stage, plan_.max_zoom, shard_ ? shard_->split_zoom : plan_.min_zoom);
            parts_ = nullptr;
          });
        });
    if (writer->tiles_written() == 0 && !shard_)  // a shard may hold no data
      throw InputError(plan_.sources[0].path +
                       ": every pixel in the requested area is transparent (nodata, mask or "
                       "alpha)" +
                       (s_.bbox ? "; check --bbox" : "") + "; nothing written");
    write_metadata(*writer);
    commit_package(*writer, s_.output, start, sum_);
    return sum_;
  }

  // Zooms top down to bottom (inclusive) into `writer`; the stage holds level
  // top + 1's pixels (nothing at the finest zoom) or a resumed build's.
  void levels(tileformat::PackageWriter& writer, StagingStore& stage, int top, int bottom) {
    const StageCheckpoint start = resume_point(stage, writer, top);
    if (start.z < top) count_finished_levels(writer, top, start.z);
    warpers_.resize(threads_);
    for (int z = top; z >= bottom; --z) {
      if (z > start.z) {  // finished before the interruption
        if (writer.tiles_at_zoom(z) > 0) coarsest_written_ = z;
        continue;
      }
      const StageCheckpoint from = z == start.z ? start : StageCheckpoint{z, 0, 0, 0};
      level_puts_ = from.puts;
      skip_puts_ = writer.resumed() ? writer.tiles_at_zoom(z) - from.puts : 0;
      if (z == plan_.max_zoom)
        pass_warp(stage, writer, z, from.done);
      else
        pass_pyramid(stage, writer, z, from.done);
      writer.checkpoint();  // the package holds level z before the stage forgets z + 1
      stage.drop(Stage::kRaw, z + 1);
      stage.commit({z - 1, 0, 0, 0});
    }
    warpers_.clear();
  }

  int coarsest_written() const { return coarsest_written_; }
  const ImageSummary& formats() const { return sum_; }

 private:
  // Where a resumed build starts: in the level the stage was working on, at
  // its last checkpoint whose tiles the package had all committed (stage
  // and package commit independently; the package's commits fall where the
  // tile sequence puts them, so that the file's bytes never depend on when
  // a build was killed). A new build, or one without a stage, starts at the
  // finest zoom from the first item.
  StageCheckpoint resume_point(StagingStore& stage, tileformat::PackageWriter& writer, int top) {
    StageCheckpoint start{top, 0, 0, 0};
    if (!writer.resumed()) return start;
    const std::optional<StageCheckpoint> last = stage.checkpoint();
    if (!last) return start;
    start = {last->z, 0, 0, 0};
    const uint64_t committed = writer.tiles_at_zoom(last->z);
    for (const StageCheckpoint& c : stage.checkpoints(last->z))
      if (c.puts <= committed) start = c;
    if (start.z < top || start.done > 0)
      progress_.note("continuing at zoom " + std::to_string(start.z) + " after " +
                     std::to_string(start.done) + " items");
    return start;
  }

  // The tile formats of the levels a resumed build finished before the
  // interruption (finer than `start_z`): the metadata says whether any tile
  // is PNG, and must not depend on where the build was killed (a kill after
  // the last level and before the rename left nothing to count).
  void count_finished_levels(tileformat::PackageWriter& writer, int top, int start_z) {
    tileformat::PackageReader done(writer.temp_path());
    for (int z = top; z > start_z && z >= plan_.min_zoom; --z)
      done.for_each_tile([&](TileId, std::span<const uint8_t> blob) { count_format(blob); }, z);
  }
  void count_format(std::span<const uint8_t> blob) {
    switch (tileformat::inspect_image_tile(blob).format) {
      case tileformat::ImageFormat::kPng:
        ++sum_.png;
        break;
      case tileformat::ImageFormat::kJpeg:
        ++sum_.jpeg;
        break;
      case tileformat::ImageFormat::kWebp:
        ++sum_.webp;
        break;
    }
  }

  // Encodes a tile and, unless it is the coarsest zoom, keeps its pixels.
  std::optional<TileOut> finish(TileId id, const TilePixels& px) const {
    if (px.empty()) return std::nullopt;
    TileOut out{id, {}, encode_image_tile(px, {s_.format, s_.quality, s_.png_level})};
    if (id.z > plan_.min_zoom) out.stage = tileformat::zstd_compress(px.planes, kStageZstdLevel);
    return out;
  }

  void store(StagingStore& stage, tileformat::PackageWriter& writer, const TileOut& out) {
    if (!out.stage.empty()) stage.put(Stage::kRaw, out.id, out.stage);
    ++level_puts_;
    if (skip_puts_ > 0) {
      --skip_puts_;  // committed before an interruption
    } else {
      writer.put_tile(out.id, out.blob);
      // The merge builds the zooms above a shard's split zoom from these.
      if (parts_ && out.id.z == shard_->split_zoom) parts_->put(kShardPixels, out.id, out.stage);
    }
    coarsest_written_ = out.id.z;
    count_format(out.blob);
  }

  // From group `first` on (a resumed build).
  void pass_warp(StagingStore& stage, tileformat::PackageWriter& writer, int z, size_t first) {
    const std::vector<TileId> tiles = tiles_in_areas(plan_.tiling, plan_.data_areas, z);
    const int g = plan_.tiling.tiles_x(z) >= 16 ? ImageWarper::kMaxGroup : 1;
    // The same groups as the whole build (a group's GDAL call decides its
    // pixels); a shard warps those holding its tiles. Tiles do not depend
    // on their neighbours: no halo.
    std::vector<WarpGroup> groups = group_tiles(tiles, g);
    if (shard_)
      std::erase_if(groups, [&](const WarpGroup& group) {
        return std::none_of(group.members.begin(), group.members.end(),
                            [&](TileId id) { return shard_->contains(id); });
      });
    size_t members = 0;
    for (const WarpGroup& group : groups)
      members += group.members.size();
    progress_.begin("z" + std::to_string(z) + " warp", members);
    for (size_t i = 0; i < first && i < groups.size(); ++i)
      progress_.advance(groups[i].members.size());
    parallel_batches<NoInputs, std::vector<TileOut>>(
        groups.size(), threads_, std::max<size_t>(2, size_t(2 * threads_)),
        [](size_t, size_t) { return NoInputs{}; },
        [&](size_t i, int worker, const NoInputs&) { return warp_group(groups[i], worker); },
        [&](size_t i, std::vector<TileOut>&& outs) {
          for (const TileOut& out : outs)
            store(stage, writer, out);
          progress_.advance(groups[i].members.size());
        },
        [&](size_t done) {
          stage.commit_if_due({z, 0, done, level_puts_});
        },
        first);
    progress_.end();
  }

  std::vector<TileOut> warp_group(const WarpGroup& grp, int worker) {
    if (!warpers_[worker]) warpers_[worker] = std::make_unique<ImageWarper>(plan_, s_);
    std::vector<uint8_t> planes;
    warpers_[worker]->warp(grp.first, grp.cols, grp.rows, planes);
    const int n = s_.tile_size, w = grp.cols * n, h = grp.rows * n;
    std::vector<TileOut> outs;
    TilePixels px(n, plan_.colour);
    for (const TileId& id : grp.members) {
      if (shard_ && !shard_->contains(id)) continue;
      const size_t ox = size_t(id.x - grp.first.x) * n, oy = size_t(id.y - grp.first.y) * n;
      for (int b = 0; b <= plan_.colour; ++b)
        for (int y = 0; y < n; ++y)
          std::copy_n(planes.data() + size_t(b) * w * h + (oy + y) * w + ox, n,
                      px.plane(b) + size_t(y) * n);
      if (auto out = finish(id, px)) outs.push_back(std::move(*out));
    }
    return outs;
  }

  // From tile `first` on (a resumed build).
  void pass_pyramid(StagingStore& stage, tileformat::PackageWriter& writer, int z, size_t first) {
    std::vector<TileId> tiles;
    for (const TileId& c : stage.list(Stage::kRaw, z + 1))
      tiles.push_back(c.parent());
    sort_tiles(tiles);
    using Blobs = std::map<TileId, std::vector<uint8_t>>;
    const size_t planes_bytes = size_t(plan_.colour + 1) * s_.tile_size * s_.tile_size;
    progress_.begin("z" + std::to_string(z) + " pyramid", tiles.size());
    progress_.advance(first);
    parallel_batches<Blobs, std::optional<TileOut>>(
        tiles.size(), threads_, size_t(8 * threads_),
        [&](size_t begin, size_t end) {
          Blobs children;
          for (size_t i = begin; i < end; ++i)
            for (const TileId& c : tiles[i].children())
              if (auto b = stage.get(Stage::kRaw, c)) children.emplace(c, std::move(*b));
          return children;
        },
        [&](size_t i, int, const Blobs& children) {
          std::array<std::optional<TilePixels>, 4> kids;
          std::array<const TilePixels*, 4> ptrs{};
          const auto ids = tiles[i].children();
          for (int c = 0; c < 4; ++c) {
            auto it = children.find(ids[c]);
            if (it == children.end()) continue;
            kids[c].emplace(s_.tile_size, plan_.colour);
            kids[c]->planes =
                tileformat::zstd_decompress(it->second, planes_bytes, "staged pixels", "3.1");
            ptrs[c] = &*kids[c];
          }
          return finish(tiles[i], downsample_children(ptrs, s_.tile_size, plan_.colour));
        },
        [&](size_t, std::optional<TileOut>&& out) {
          if (out) store(stage, writer, *out);
          progress_.advance();
        },
        [&](size_t done) {
          stage.commit_if_due({z, 0, done, level_puts_});
        },
        first);
    progress_.end();
  }

  // The data's lon/lat bounds. In the global schemes they are snapped
  // outward to the finest zoom's pixel edges: GDAL's MBTiles driver takes
  // `bounds` as its raster origin but reads pixels at the rounded offset, so
  // unsnapped bounds would shift its georeferencing by up to half a pixel.
  tileformat::Bounds metadata_bounds() const {
    const auto& t = plan_.tiling;
    if (t.scheme == tileformat::Scheme::kLocal) return plan_.lonlat;
    tileformat::Bounds u = plan_.data_areas[0];
    for (const auto& a : plan_.data_areas)
      u = {std::min(u.min_x, a.min_x), std::min(u.min_y, a.min_y), std::max(u.max_x, a.max_x),
           std::max(u.max_y, a.max_y)};
    const double px = t.sample_spacing(plan_.max_zoom, s_.tile_size);
    const tileformat::Bounds ext = t.extent();
    auto down = [&](double v, double o) { return o + std::floor((v - o) / px + 1e-6) * px; };
    auto up = [&](double v, double o) { return o + std::ceil((v - o) / px - 1e-6) * px; };
    u = {std::max(ext.min_x, down(u.min_x, ext.min_x)),
         std::max(ext.min_y, down(u.min_y, ext.min_y)), std::min(ext.max_x, up(u.max_x, ext.min_x)),
         std::min(ext.max_y, up(u.max_y, ext.min_y))};
    if (t.scheme == tileformat::Scheme::kGeodetic) return u;
    constexpr double kPi = 3.14159265358979323846, kR = 6378137.0;
    auto lon = [&](double x) { return x / kR * 180.0 / kPi; };
    auto lat = [&](double y) { return std::atan(std::sinh(y / kR)) * 180.0 / kPi; };
    return {lon(u.min_x), lat(u.min_y), lon(u.max_x), lat(u.max_y)};
  }

  void write_metadata(tileformat::PackageWriter& w) const {
    std::vector<tileformat::InputFile> inputs;
    for (const auto& src : plan_.sources)
      inputs.push_back({src.path, src.file_bytes});
    tileformat::ImageMetadata m;
    m.common =
        raster_common_metadata({s_.output, tileformat::image_format_name(s_.format), "Imagery",
                                s_.command_line, coarsest_written_, plan_.max_zoom},
                               std::move(inputs), plan_);
    m.common.lonlat = metadata_bounds();
    m.common.bounds_digits = 0;  // snapped bounds must survive the round trip
    m.format = s_.format;
    m.resampling = s_.resampling;
    m.tile_size = s_.tile_size;
    m.colour_bands = plan_.colour;
    if (s_.format != tileformat::ImageFormat::kPng) m.quality = s_.quality;
    // A shard always says (the merge may write PNG tiles the shard did not).
    if (sum_.png || shard_) m.png_level = s_.png_level;
    m.scale = plan_.scale;
    w.set_metadata(tileformat::to_metadata(m));
    // Imagery has tiles down to the coarsest zoom wherever it has data.
    if (shard_)
      w.set_metadata(tileformat::to_metadata(shard_metadata(
          s_, *shard_, plan_.min_zoom, raster_center_zoom(plan_, plan_.min_zoom, plan_.max_zoom))));
  }

  const ImagePlan& plan_;
  const ImageSettings& s_;
  Progress& progress_;
  const int threads_;
  const ShardPlan* shard_;
  tileformat::ShardTableWriter* parts_ = nullptr;  // a shard's, while its levels are built
  std::vector<std::unique_ptr<ImageWarper>> warpers_;
  int coarsest_written_ = 0;
  uint64_t level_puts_ = 0;  // tiles of this level stored so far (put or skipped)
  uint64_t skip_puts_ = 0;   // of the next ones, how many a resumed package already holds
  ImageSummary sum_;
};

}  // namespace

ImageSummary build_imagery(const ImagePlan& plan, const ImageSettings& settings,
                           Progress& progress) {
  if (!settings.shard) return Builder(plan, settings, progress).run();
  // Work per subtree: its finest tiles, weighted by how much of them the
  // sources cover with opaque pixels.
  std::vector<ProbeBand> bands;
  for (const ImageSource& src : plan.sources)
    bands.push_back(src.alpha_band ? ProbeBand{src.alpha_band, true, std::nullopt}
                                   : ProbeBand{src.colour_bands.at(0), false, settings.nodata});
  const ShardPlan shard = plan_raster_shard(plan, {plan.sources.begin(), plan.sources.end()}, bands,
                                            settings, progress);
  return Builder(plan, settings, progress, &shard).run();
}

ImageLevels build_imagery_levels(const ImagePlan& plan, const ImageSettings& settings,
                                 tileformat::PackageWriter& writer, StagingStore& stage, int top,
                                 Progress& progress) {
  Builder b(plan, settings, progress);
  b.levels(writer, stage, top, plan.min_zoom);
  return {b.coarsest_written(), b.formats()};
}

}  // namespace globe
