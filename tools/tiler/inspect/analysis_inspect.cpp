// info, validate and extract for analysis packages (tileformat §9).
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>

#include "inspect/inspect_commands.hpp"
#include "kit/package_info.hpp"
#include "kit/validation_report.hpp"
#include "runtime/analysis_package.hpp"
#include "runtime/errors.hpp"
#include "tileformat/error.hpp"

namespace globe {

using tileformat::TileId;
namespace {

using tileformat::AnalysisLayer;

std::string layer_list(const std::vector<AnalysisLayer>& layers) {
  std::string s;
  for (AnalysisLayer l : layers) {
    const auto& i = tileformat::analysis_layer_info(l);
    s += (s.empty() ? "" : ", ") + std::string(i.name) + " (" + i.unit + ")";
  }
  return s;
}

// "sky view: ..." for info: directions, radius, and the zooms whose rays
// reach less (the zooms above them ran out: analysis_builder.cpp).
std::string skyview_line(const tileformat::AnalysisMetadata& m) {
  char buf[160];
  std::snprintf(buf, sizeof buf, "sky view: %d directions, radius %g m", m.skyview_directions,
                m.skyview_radius_m);
  std::string s = buf, shorter;
  for (const auto& [z, r] : m.skyview_radius_by_zoom)
    if (r < m.skyview_radius_m) {
      std::snprintf(buf, sizeof buf, "%szoom %d %.0f m", shorter.empty() ? "" : ", ", z, r);
      shorter += buf;
    }
  if (m.skyview_radius_by_zoom.empty())
    s += " (reach per zoom not recorded: made before 2026-11-28)";
  else if (shorter.empty())
    s += ", reached at every zoom";
  else
    s += "; reached except at " + shorter +
         " (no coarser zoom to draw the far field from: build the terrain from a lower "
         "--min-zoom)";
  return s;
}

int analysis_info(const std::string& path, bool json) {
  AnalysisPackage p = open_analysis_package(path);
  if (json) {
    std::vector<InfoJson> layers;
    for (AnalysisLayer l : p.meta.layers) {
      const auto& i = tileformat::analysis_layer_info(l);
      layers.push_back(InfoJson().text("name", i.name).text("unit", i.unit));
    }
    InfoJson a;
    a.objects("layers", layers).text("terrain", p.meta.terrain).integer("block_size", p.block_size);
    if (p.meta.skyview_directions > 0) {
      std::vector<InfoJson> by_zoom;
      for (const auto& [z, r] : p.meta.skyview_radius_by_zoom)
        by_zoom.push_back(InfoJson().integer("zoom", uint64_t(z)).number("radius_m", r));
      a.object("skyview", InfoJson()
                              .integer("directions", uint64_t(p.meta.skyview_directions))
                              .number("radius_m", p.meta.skyview_radius_m)
                              .objects("radius_by_zoom", by_zoom));
    }
    print_kind_info_json(p.file(), path, tileformat::PackageKind::kAnalysis, a);
    return kExitOk;
  }
  print_package_info(p.file(), path);
  std::printf("analysis: %s; from terrain %s; %d x %d samples per block\n",
              layer_list(p.meta.layers).c_str(), p.meta.terrain.c_str(), p.block_size,
              p.block_size);
  if (p.meta.skyview_directions > 0) std::printf("%s\n", skyview_line(p.meta).c_str());
  return kExitOk;
}

int validate_analysis(const std::string& path) {
  AnalysisPackage p = open_analysis_package(path);
  ValidationReport r;
  if (p.file().application_id() != tileformat::kApplicationId)
    r.warning("PRAGMA application_id is not 0x4d504258 (tileformat §3.1)");
  uint64_t tiles = 0;
  p.file().for_each_tile([&](tileformat::TileId id, std::span<const uint8_t> blob) {
    ++tiles;
    const std::string where = "tile " + id.str();
    if (!p.tiling.contains(id) || id.z < p.min_zoom || id.z > p.max_zoom) {
      r.error(where + ": outside the tiling or the zoom range");
      return;
    }
    try {
      const tileformat::AnalysisBlock b = tileformat::decode_analysis_block(blob);
      if (b.size != p.block_size)
        r.error(where + ": size " + std::to_string(b.size) + " differs from globe:block_size");
      if (b.layers != p.meta.layers)
        r.error(where + ": layers differ from globe:analysis_layers (tileformat §9)");
    } catch (const tileformat::FormatError& e) {
      r.error(where + ": " + e.what());
    }
  });
  std::printf("%llu tiles checked: %llu errors, %llu warnings\n",
              static_cast<unsigned long long>(tiles), static_cast<unsigned long long>(r.errors),
              static_cast<unsigned long long>(r.warnings));
  return r.exit_code();
}

int extract_analysis(const ExtractRequest& rq) {
  AnalysisPackage p = open_analysis_package(rq.package);
  if (rq.layer.empty())
    throw UsageError("--layer is required for an analysis package; it holds " +
                     layer_list(p.meta.layers));
  const auto layer = tileformat::analysis_layer_by_name(rq.layer);
  size_t index = 0;
  while (layer && index < p.meta.layers.size() && p.meta.layers[index] != *layer)
    ++index;
  if (!layer || index == p.meta.layers.size())
    throw UsageError("--layer " + rq.layer + ": " + rq.package + " holds " +
                     layer_list(p.meta.layers));
  const auto& info = tileformat::analysis_layer_info(*layer);
  const ExtractTiles t = tiles_to_extract(p.file(), p.tiling, rq, p.min_zoom, p.max_zoom);
  const SampleGrid grid = write_block_samples(
      rq, p.tiling, t, p.block_size, GDT_Float32, [&](TileId id, std::vector<double>& samples) {
        tileformat::AnalysisBlock b;
        try {
          b = tileformat::decode_analysis_block(*p.reader->tile(id));
        } catch (const tileformat::FormatError& e) {
          throw InputError(rq.package + ": tile " + id.str() + ": " + e.what());
        }
        const std::vector<uint16_t>& v = b.values[index];
        for (size_t i = 0; i < samples.size(); ++i)
          samples[i] = v[i] == tileformat::kNoValue ? std::numeric_limits<double>::quiet_NaN()
                                                    : tileformat::dequantize(info, v[i]);
      });
  std::fprintf(stderr, "globe-tiler: wrote %s: %s, %llu x %llu samples from %zu tiles of zoom %d\n",
               rq.output.c_str(), info.name, static_cast<unsigned long long>(grid.width),
               static_cast<unsigned long long>(grid.height), t.ids.size(), rq.zoom);
  return kExitOk;
}

}  // namespace

// This kind's row of the tool's table (inspect/inspect_commands.cpp).
extern const KindInspection kAnalysisInspection{tileformat::PackageKind::kAnalysis, analysis_info,
                                                validate_analysis, extract_analysis};

}  // namespace globe
