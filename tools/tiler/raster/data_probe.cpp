// Work estimate from a coarse read of the inputs (see data_probe.hpp).
#include "raster/data_probe.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "geo/spatial_ref.hpp"
#include "raster/tile_groups.hpp"

namespace globe {
namespace {

using tileformat::TileId;

constexpr int kProbePixels = 512;
constexpr uint64_t kSamplesPerCell = 16;

struct Count {
  uint64_t all = 0, valid = 0;
};

}  // namespace

std::vector<TileWork> probe_tile_work(const Footprint& footprint,
                                      const std::vector<RasterSource>& sources,
                                      const std::vector<ProbeBand>& bands,
                                      const std::vector<TileId>& tiles) {
  if (tiles.empty()) return {};
  const tileformat::Tiling& tiling = footprint.tiling;
  const int zf = tiles.front().z;
  // Probe pixels at the finest zoom (x, y of the tile), valid or not.
  std::map<TileId, Count> finest;
  const SpatialRef target = SpatialRef::from_wkt(tiling.crs, "the tiling");
  for (size_t s = 0; s < sources.size(); ++s) {
    const RasterSource& src = sources[s];
    const GdalDataset ds = GdalDataset::open_raster(src.path);
    const int w = std::min(src.width, kProbePixels), h = std::min(src.height, kProbePixels);
    std::vector<double> v(size_t(w) * h);
    const ProbeBand& band = bands[s];
    ds.read_shrunk(band.band, w, h, v.data());
    const std::optional<double> nodata = band.nodata ? band.nodata : ds.nodata(band.band);
    const SpatialRef crs = SpatialRef::from_wkt(src.crs_wkt, src.path);
    const CoordTransform to_target(crs, target);
    const auto& gt = src.geotransform;
    for (double shift : src.x_shifts) {
      std::vector<double> xs, ys;
      std::vector<uint8_t> ok;
      for (int j = 0; j < h; ++j)
        for (int i = 0; i < w; ++i) {
          const double px = (i + 0.5) * src.width / w, py = (j + 0.5) * src.height / h;
          xs.push_back(gt[0] + px * gt[1] + py * gt[2] + shift);
          ys.push_back(gt[3] + px * gt[4] + py * gt[5]);
          const double value = v[size_t(j) * w + i];
          ok.push_back(band.alpha ? value > 0
                                  : std::isfinite(value) && !(nodata && value == *nodata));
        }
      std::vector<int> placed;
      to_target.transform(xs, ys, placed);
      const double size = tiling.tile_size(zf);
      for (size_t k = 0; k < xs.size(); ++k) {
        if (!placed[k]) continue;
        const double fx = std::floor((xs[k] - tiling.origin_x) / size),
                     fy = std::floor((tiling.origin_y - ys[k]) / size);
        if (!(fx >= 0 && fy >= 0 && fx < double(tiling.tiles_x(zf)) &&
              fy < double(tiling.tiles_y(zf))))
          continue;
        Count& c = finest[TileId{zf, static_cast<uint32_t>(fx), static_cast<uint32_t>(fy)}];
        ++c.all;
        c.valid += ok[k];
      }
    }
  }
  // The finest zoom whose tiles with probe pixels average at least
  // kSamplesPerCell of them (zoom 0 at worst).
  uint64_t probes = 0;
  for (const auto& [id, c] : finest)
    probes += c.all;
  int zc = zf;
  auto cells_at = [&](int z) {
    std::map<TileId, Count> cells;
    for (const auto& [id, c] : finest) {
      Count& cell = cells[TileId{z, id.x >> (zf - z), id.y >> (zf - z)}];
      cell.all += c.all;
      cell.valid += c.valid;
    }
    return cells;
  };
  std::map<TileId, Count> cells = cells_at(zc);
  while (zc > 0 && !cells.empty() && probes < kSamplesPerCell * cells.size())
    cells = cells_at(--zc);
  std::vector<TileWork> work;
  work.reserve(tiles.size());
  for (const TileId& t : tiles) {
    auto it = cells.find(TileId{zc, t.x >> (zf - zc), t.y >> (zf - zc)});
    const double share =
        it == cells.end() || it->second.all == 0 ? 0.0 : double(it->second.valid) / it->second.all;
    work.push_back({t, 4 + static_cast<uint64_t>(std::lround(8 * share))});
  }
  return work;
}

ShardPlan plan_raster_shard(const Footprint& footprint, const std::vector<RasterSource>& sources,
                            const std::vector<ProbeBand>& bands, const BuildOptions& o,
                            Progress& progress) {
  const std::vector<TileWork> work =
      probe_tile_work(footprint, sources, bands,
                      tiles_in_areas(footprint.tiling, footprint.data_areas, footprint.max_zoom));
  ShardPlan shard = plan_shard(work, footprint.min_zoom, o.split_zoom, *o.shard);
  progress.note(shard_summary(shard, *o.shard));
  return shard;
}

}  // namespace globe
