// The analysis builder (see analysis_builder.hpp).
#include "analysis/analysis_builder.hpp"

#include <chrono>
#include <cmath>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <set>

#include "analysis/batch_blocks.hpp"
#include "analysis/flow/flow_solver.hpp"
#include "analysis/height_levels.hpp"
#include "analysis/sky_view.hpp"
#include "analysis/terrain_derivatives.hpp"
#include "kit/package_output.hpp"
#include "kit/parallel_batches.hpp"
#include "kit/shard_plan.hpp"
#include "runtime/errors.hpp"
#include "runtime/terrain_package.hpp"
#include "tileformat/error.hpp"
#include "tileformat/mblock.hpp"
#include "tileformat/metadata.hpp"
#include "tileformat/shard_table.hpp"

namespace globe {
namespace {

using tileformat::AnalysisLayer;
using tileformat::TileId;

bool has_layer(const std::vector<AnalysisLayer>& layers, AnalysisLayer l) {
  return std::find(layers.begin(), layers.end(), l) != layers.end();
}

class BlockAnalyzer {
 public:
  BlockAnalyzer(const TerrainPackage& p, const AnalysisSettings& s, const flow::FlowPyramid* flow)
      : p_(p), s_(s), flow_(flow) {}

  // Whether a layer reads the terrain's heights (the flow layers come from
  // the solved grid).
  bool reads_heights() const {
    return std::any_of(s_.layers.begin(), s_.layers.end(),
                       [](AnalysisLayer l) { return l <= AnalysisLayer::kSkyview; });
  }

  // Samples around a block that its layers read, at its own zoom and (sky
  // view past two blocks) at its ancestors' zooms.
  std::vector<int> halos(TileId id) const {
    const int n = p_.block_size - 1;
    if (!has_layer(s_.layers, AnalysisLayer::kSkyview)) return {1};
    double spacing = 1e300;
    for (int row : {0, n}) {
      const GroundSpacing g = ground_spacing(p_.tiling, id.z, n, id.y, row);
      spacing = std::min({spacing, g.dx, g.dy});
    }
    std::vector<int> h = sky_view_reach(s_.skyview, spacing, n, id.z - p_.min_zoom).halos;
    h[0] = std::max(h[0], 1);
    return h;
  }

  std::vector<uint8_t> analyze(TileId id, const BatchBlocks& blocks) const {
    const int s = p_.block_size, n = s - 1;
    const std::vector<AnalysisLayer>& layers = s_.layers;
    const bool skyview = has_layer(layers, AnalysisLayer::kSkyview);
    const bool flow = has_layer(layers, AnalysisLayer::kFlowDirection) ||
                      has_layer(layers, AnalysisLayer::kFlowAccumulation);
    tileformat::AnalysisBlock out;
    out.size = s;
    out.layers = layers;
    out.values.assign(layers.size(), std::vector<uint16_t>(size_t(s) * s, tileformat::kNoValue));
    // Looked up once, not per sample; the 3 x 3 derivatives only when a
    // layer draws on them (not for skyview alone).
    std::vector<const tileformat::AnalysisLayerInfo*> info;
    for (AnalysisLayer l : layers)
      info.push_back(&tileformat::analysis_layer_info(l));
    const bool local = std::any_of(layers.begin(), layers.end(), [](AnalysisLayer l) {
      return l <= AnalysisLayer::kPlanCurvature;
    });
    std::vector<uint64_t> area;
    std::vector<uint8_t> code;
    if (flow) flow_->block(id, s, area, code);
    std::optional<HeightLevels> levels;
    if (reads_heights())
      levels.emplace(p_.tiling, id, s, halos(id),
                     [&](TileId t) { return blocks.get(t, s_.inputs[0]); });
    for (int y = 0; levels && y < s; ++y) {
      const HeightWindow& w = levels->own();
      const GroundSpacing sp = ground_spacing(p_.tiling, id.z, n, id.y, y);
      std::vector<double> sky;
      if (skyview) {
        sky.resize(size_t(s));
        SkyViewScan(s_.skyview, sp).row(*levels, y, s, sky.data());
      }
      for (int x = 0; x < s; ++x) {
        if (!w.valid(x, y)) continue;
        Derivatives d;
        if (local) {
          Window3 w3;
          for (int j = 0; j < 3; ++j)
            for (int i = 0; i < 3; ++i)
              w3.z[j * 3 + i] =
                  w.valid(x + i - 1, y + j - 1) ? w.height(x + i - 1, y + j - 1) : w.height(x, y);
          d = derivatives(w3, sp.dx, sp.dy);
        }
        for (size_t l = 0; l < layers.size(); ++l) {
          double v = 0;
          switch (layers[l]) {
            case AnalysisLayer::kSlope:
              v = d.slope_deg;
              break;
            case AnalysisLayer::kAspect:
              v = d.aspect_deg;
              break;
            case AnalysisLayer::kProfileCurvature:
              v = d.profile;
              break;
            case AnalysisLayer::kPlanCurvature:
              v = d.plan;
              break;
            case AnalysisLayer::kSkyview:
              v = sky[size_t(x)];
              break;
            case AnalysisLayer::kFlowDirection:
            case AnalysisLayer::kFlowAccumulation:
              continue;  // below: the flow has its own extent
          }
          if (!std::isnan(v)) out.values[l][size_t(y) * s + x] = tileformat::quantize(*info[l], v);
        }
      }
    }
    if (flow)
      for (size_t l = 0; l < layers.size(); ++l)
        for (size_t i = 0; i < code.size(); ++i) {
          if (code[i] == flow::kNoDataCode) continue;
          if (layers[l] == AnalysisLayer::kFlowDirection) out.values[l][i] = code[i];
          if (layers[l] == AnalysisLayer::kFlowAccumulation)
            out.values[l][i] =
                tileformat::quantize(*info[l], double(area[i]) / flow::kAreaUnitsPerM2);
        }
    return tileformat::encode_analysis_block(out);
  }

 private:
  const TerrainPackage& p_;
  const AnalysisSettings& s_;
  const flow::FlowPyramid* flow_;
};

// Per zoom, the radius every sample's rays reach (globe:skyview_radius_by_zoom):
// the least sky_view_reach over its tile rows, at their smallest ground
// spacing; on the geodetic tiling over latitudes within 80 degrees of the
// equator (towards the poles its east-west spacing shrinks to nothing).
std::vector<std::pair<int, double>> skyview_radius_by_zoom(const TerrainPackage& p,
                                                           const SkyViewSettings& s) {
  const int n = p.block_size - 1;
  const bool geodetic = p.tiling.scheme == tileformat::Scheme::kGeodetic;
  std::vector<std::pair<int, double>> out;
  for (int z = p.min_zoom; z <= p.max_zoom; ++z) {
    std::set<uint32_t> rows;  // the blocks of a tile row share their spacing
    for (const TileId& id : p.reader->tile_ids(z))
      rows.insert(id.y);
    const double sp = p.tiling.sample_spacing(z, n);
    double radius = s.radius_m;
    bool any = false;
    for (uint32_t ty : rows) {
      double north = p.tiling.origin_y - double(ty) * n * sp, south = north - n * sp;
      if (geodetic) {
        north = std::min(north, 80.0);
        south = std::max(south, -80.0);
        if (north < south) continue;
      }
      double spacing = 1e300;
      for (double y : {north, south, std::clamp(0.0, south, north)}) {
        const GroundSpacing g = ground_spacing_at(p.tiling, z, n, y);
        spacing = std::min({spacing, g.dx, g.dy});
      }
      radius = std::min(radius, sky_view_reach(s, spacing, n, z - p.min_zoom).radius_m);
      any = true;
    }
    if (any) out.emplace_back(z, radius);
  }
  return out;
}

tileformat::AnalysisMetadata analysis_metadata(const AnalysisSettings& s, const TerrainPackage& p) {
  tileformat::AnalysisMetadata m;
  m.common = p.meta.common;
  m.common.name = std::filesystem::path(s.output).stem().string();
  m.common.format = tileformat::kAnalysisFormat;
  m.common.type = "overlay";
  std::error_code ec;
  const auto bytes = std::filesystem::file_size(s.inputs[0], ec);
  m.common.inputs = {{s.inputs[0], ec ? 0 : bytes}};
  m.common.description =
      tileformat::build_description("Terrain analysis", "globe-tiler", m.common.inputs);
  m.common.generator = "globe-tiler " GLOBE_VERSION;
  m.common.command_line = s.command_line;
  m.block_size = p.block_size;
  m.layers = s.layers;
  m.terrain = std::filesystem::path(s.inputs[0]).filename().string();
  m.height_step = p.step_m;
  if (has_layer(s.layers, tileformat::AnalysisLayer::kSkyview)) {
    m.skyview_directions = s.skyview.directions;
    m.skyview_radius_m = s.skyview.radius_m;
    m.skyview_radius_by_zoom = skyview_radius_by_zoom(p, s.skyview);
  }
  if (has_layer(s.layers, tileformat::AnalysisLayer::kFlowDirection) ||
      has_layer(s.layers, tileformat::AnalysisLayer::kFlowAccumulation))
    m.flow_method = s.flow_method == flow::FlowMethod::kCarve ? "carve" : "fill";
  return m;
}

}  // namespace

AnalysisSummary build_analysis(const AnalysisSettings& s, Progress& progress) {
  const auto t0 = std::chrono::steady_clock::now();
  const std::string& path = s.inputs[0];
  TerrainPackage p = open_terrain_package(path);
  p.file().stream();  // one pass: no mapped pages held (PackageReader::stream)
  std::vector<TileId> items;
  for (int z = p.min_zoom; z <= p.max_zoom; ++z)
    for (const TileId& id : p.reader->tile_ids(z))
      items.push_back(id);
  // A shard: its subtrees below the split zoom (work: the terrain's finest
  // blocks; every analysis block reads only the terrain, so no halo is
  // computed), and for shard 0 the few levels above the split too, so the
  // merge only copies.
  std::optional<ShardPlan> shard;
  if (s.shard) {
    std::vector<TileWork> work;
    for (const TileId& id : p.reader->tile_ids(p.max_zoom))
      work.push_back({id, 1});
    shard = plan_shard(work, p.min_zoom, s.split_zoom, *s.shard);
    std::erase_if(items, [&](TileId id) {
      return id.z < shard->split_zoom ? s.shard->index != 0 : !shard->contains(id);
    });
    progress.note(shard_summary(*shard, *s.shard) +
                  (s.shard->index == 0 ? ", and the zooms above" : ""));
  }
  AnalysisSummary sum;
  std::unique_ptr<tileformat::PackageWriter> writer = create_package(s, progress);
  write_package_tiles(s.output, [&] {
    if (shard)  // the roots in the first transaction (see ShardTableWriter)
      tileformat::ShardTableWriter(*writer).put_roots(shard->roots);
    // Tiles are written in item order and committed in that order: a
    // resumed build's package holds a prefix of the items.
    size_t first = 0;
    if (writer->resumed())
      for (int z = p.min_zoom; z <= p.max_zoom; ++z)
        first += writer->tiles_at_zoom(z);
    // Flow first: the whole finest zoom, out of core, before any tile.
    flow::FlowSolution flow;
    if (has_layer(s.layers, AnalysisLayer::kFlowDirection) ||
        has_layer(s.layers, AnalysisLayer::kFlowAccumulation)) {
      flow::FlowSettings fs;
      fs.memory_bytes = s.memory_mb << 20;
      fs.chunk = s.flow_chunk;
      fs.method = s.flow_method;
      fs.threads = s.worker_threads();
      fs.scratch_prefix = s.output + ".flow-";
      fs.input = path;
      flow = flow::solve_flow(p, fs, progress);
      const flow::FlowGrid& g = *flow.grid;
      sum.flow_note =
          "flow: " + std::to_string(g.width()) + " x " + std::to_string(g.height()) + " cells";
      if (flow.method == flow::FlowMethod::kCarve)
        sum.flow_note += ", routed by least cost in memory (--flow-method carve)";
      else
        sum.flow_note +=
            " in " + std::to_string(g.chunks().size()) + " chunks of " +
            std::to_string(g.chunk_size()) +
            (flow.scratch_in_memory ? " (scratch in memory), " : " (scratch on disk), ") +
            std::to_string(flow.watersheds) + " watersheds, " + std::to_string(flow.flat_rounds) +
            " flat rounds";
    }
    const BlockAnalyzer analyzer(p, s, flow.pyramid.get());
    progress.begin("analyze", items.size());
    progress.advance(first);
    parallel_batches<BatchBlocks, std::vector<uint8_t>>(
        items.size(), s.worker_threads(), 64,
        [&](size_t begin, size_t end) {
          BatchBlocks blocks;
          if (!analyzer.reads_heights()) return blocks;  // flow layers only
          for (size_t i = begin; i < end; ++i) {
            for (const TileId& t :
                 HeightLevels::tiles(p.tiling, items[i], p.block_size, analyzer.halos(items[i])))
              if (!blocks.has(t)) blocks.add(t, p.reader->tile(t));
          }
          return blocks;
        },
        [&](size_t i, int, const BatchBlocks& blocks) {
          return analyzer.analyze(items[i], blocks);
        },
        [&](size_t i, std::vector<uint8_t>&& blob) {
          writer->put_tile(items[i], blob);
          progress.advance();
        },
        [](size_t) {}, first);
    progress.end();
    const tileformat::AnalysisMetadata meta = analysis_metadata(s, p);
    writer->set_metadata(tileformat::to_metadata(meta));
    if (shard)
      writer->set_metadata(tileformat::to_metadata(
          shard_metadata(s, *shard, meta.common.min_zoom, meta.common.center_zoom)));
  });
  commit_package(*writer, s.output, t0, sum);
  sum.tiles = items.size();
  return sum;
}

}  // namespace globe
