// The analysis builder (see analysis_builder.hpp).
#include "analysis_builder.hpp"

#include <chrono>
#include <cmath>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <optional>

#include "errors.hpp"
#include "height_window.hpp"
#include "package_output.hpp"
#include "parallel_batches.hpp"
#include "sky_view.hpp"
#include "terrain_derivatives.hpp"
#include "terrain_package.hpp"
#include "tileformat/error.hpp"
#include "tileformat/mblock.hpp"
#include "tileformat/metadata.hpp"

namespace globe {
namespace {

using tileformat::AnalysisLayer;
using tileformat::TileId;

// The terrain blocks one batch of work reads, each decoded once, by the
// first worker that needs it.
class BatchBlocks {
 public:
  void add(TileId id, std::optional<std::vector<uint8_t>> blob) {
    if (slots_.count(id)) return;
    auto slot = std::make_unique<Slot>();
    slot->blob = std::move(blob);
    slots_.emplace(id, std::move(slot));
  }
  bool has(TileId id) const { return slots_.count(id) != 0; }
  // Null where there is no tile. Throws InputError for a corrupt block.
  const tileformat::MBlock* get(TileId id, const std::string& path) const {
    const auto it = slots_.find(id);
    if (it == slots_.end() || !it->second->blob) return nullptr;
    Slot& s = *it->second;
    std::call_once(s.once, [&] {
      try {
        s.block = tileformat::decode_mblock(*s.blob);
      } catch (const tileformat::FormatError& e) {
        throw InputError(path + ": tile " + id.str() + ": " + e.what() +
                         "; rebuild the terrain package (globe-tiler validate lists bad tiles)");
      }
    });
    return &s.block;
  }

 private:
  struct Slot {
    std::optional<std::vector<uint8_t>> blob;
    std::once_flag once;
    tileformat::MBlock block;
  };
  std::map<TileId, std::unique_ptr<Slot>> slots_;
};

bool has_layer(const std::vector<AnalysisLayer>& layers, AnalysisLayer l) {
  return std::find(layers.begin(), layers.end(), l) != layers.end();
}

class BlockAnalyzer {
 public:
  BlockAnalyzer(const TerrainPackage& p, const AnalysisSettings& s) : p_(p), s_(s) {}

  // Samples around a block that its layers read.
  int halo(TileId id) const {
    const int n = p_.block_size - 1;
    if (!has_layer(s_.layers, AnalysisLayer::kSkyview)) return 1;
    double spacing = 1e300;
    for (int row : {0, n}) {
      const GroundSpacing g = ground_spacing(p_.tiling, id.z, n, id.y, row);
      spacing = std::min({spacing, g.dx, g.dy});
    }
    return std::max(1, sky_view_halo(s_.skyview, spacing, n));
  }

  std::vector<uint8_t> analyze(TileId id, const BatchBlocks& blocks) const {
    const int s = p_.block_size, n = s - 1;
    const HeightWindow w(p_.tiling, id, s, halo(id),
                         [&](TileId t) { return blocks.get(t, s_.inputs[0]); });
    const std::vector<AnalysisLayer>& layers = s_.layers;
    const bool skyview = has_layer(layers, AnalysisLayer::kSkyview);
    tileformat::AnalysisBlock out;
    out.size = s;
    out.layers = layers;
    out.values.assign(layers.size(), std::vector<uint16_t>(size_t(s) * s, tileformat::kNoValue));
    // Looked up once, not per sample; the 3 x 3 derivatives only when a
    // layer draws on them (not for skyview alone).
    std::vector<const tileformat::AnalysisLayerInfo*> info;
    for (AnalysisLayer l : layers)
      info.push_back(&tileformat::analysis_layer_info(l));
    const bool local = layers.size() > (skyview ? 1u : 0u);
    for (int y = 0; y < s; ++y) {
      const GroundSpacing sp = ground_spacing(p_.tiling, id.z, n, id.y, y);
      std::optional<SkyViewScan> scan;
      if (skyview) scan.emplace(s_.skyview, sp);
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
              v = scan->factor(w, x, y);
              break;
          }
          if (!std::isnan(v)) out.values[l][size_t(y) * s + x] = tileformat::quantize(*info[l], v);
        }
      }
    }
    return tileformat::encode_analysis_block(out);
  }

 private:
  const TerrainPackage& p_;
  const AnalysisSettings& s_;
};

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
  }
  return m;
}

}  // namespace

AnalysisSummary build_analysis(const AnalysisSettings& s, Progress& progress) {
  const auto t0 = std::chrono::steady_clock::now();
  const std::string& path = s.inputs[0];
  TerrainPackage p = open_terrain_package(path);
  std::vector<TileId> items;
  for (int z = p.min_zoom; z <= p.max_zoom; ++z)
    for (const TileId& id : p.reader->tile_ids(z))
      items.push_back(id);
  AnalysisSummary sum;
  try {
    std::unique_ptr<tileformat::PackageWriter> writer = create_package(s, progress);
    // Tiles are written in item order and committed in that order: a
    // resumed build's package holds a prefix of the items.
    size_t first = 0;
    if (writer->resumed())
      for (int z = p.min_zoom; z <= p.max_zoom; ++z)
        first += writer->tiles_at_zoom(z);
    const BlockAnalyzer analyzer(p, s);
    progress.begin("analyze", items.size());
    progress.advance(first);
    parallel_batches<BatchBlocks, std::vector<uint8_t>>(
        items.size(), s.worker_threads(), 64,
        [&](size_t begin, size_t end) {
          BatchBlocks blocks;
          for (size_t i = begin; i < end; ++i) {
            const int radius = HeightWindow::radius_for(p.block_size, analyzer.halo(items[i]));
            for (const TileId& t : tiles_around(p.tiling, items[i], radius))
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
    writer->set_metadata(tileformat::to_metadata(analysis_metadata(s, p)));
    sum.tiles = items.size();
    sum.unique_blobs = writer->unique_blobs();
    sum.file_bytes = commit_package(*writer, s.output);
  } catch (const tileformat::PackageError& e) {
    throw build_write_error(s.output, e);
  }
  sum.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return sum;
}

}  // namespace globe
