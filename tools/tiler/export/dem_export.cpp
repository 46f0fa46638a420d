// Raster-DEM export (see dem_export.hpp).
#include "export/dem_export.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <memory>
#include <vector>

#include "kit/parallel_batches.hpp"
#include "runtime/errors.hpp"
#include "runtime/terrain_package.hpp"
#include "tileformat/pmtiles.hpp"
#include "web/raster_dem_tile.hpp"
#include "web/terrain_sampler.hpp"
#include "web/tile_output.hpp"

namespace globe {
namespace {

constexpr double kMaxMercatorLat = 85.0511287798066;
struct ExportTile {
  uint64_t id = 0;  // PMTiles order
  int z = 0, source_zoom = 0;
  uint32_t x = 0, y = 0;
};

struct EncodedTile {
  std::vector<uint8_t> png;
  uint64_t without_data = 0;
};

// Web mercator tiles (XYZ) of zoom z over the lon/lat box.
void tiles_over(double west, double south, double east, double north, int z, int source_zoom,
                std::vector<ExportTile>& out) {
  const double n = std::ldexp(1.0, z);
  const web::MercatorPoint a = web::lonlat_to_mercator(west, std::min(north, kMaxMercatorLat));
  const web::MercatorPoint b = web::lonlat_to_mercator(east, std::max(south, -kMaxMercatorLat));
  const double tile = 2 * web::kMercatorHalf / n;
  auto index = [&](double v) {
    return static_cast<uint32_t>(std::clamp(std::floor(v), 0.0, n - 1));
  };
  const uint32_t x0 = index((a.x + web::kMercatorHalf) / tile),
                 x1 = index((b.x + web::kMercatorHalf) / tile - 1e-9);
  const uint32_t y0 = index((web::kMercatorHalf - a.y) / tile),
                 y1 = index((web::kMercatorHalf - b.y) / tile - 1e-9);
  for (uint32_t y = y0; y <= y1; ++y)
    for (uint32_t x = x0; x <= x1; ++x)
      out.push_back({tileformat::pmtiles::tile_id(z, x, y), z, source_zoom, x, y});
}

}  // namespace

ExportSummary export_raster_dem(const DemExportSettings& s, Progress& progress) {
  const auto start = std::chrono::steady_clock::now();
  TerrainPackage pkg = open_terrain_package(s.input);
  pkg.file().stream();  // one pass: no mapped pages held (PackageReader::stream)
  const tileformat::Scheme scheme = pkg.tiling.scheme;
  if (scheme == tileformat::Scheme::kLocal)
    throw UsageError(s.input +
                     ": a package in a local tiling cannot become web mercator tiles; build it "
                     "with --tiling webmercator or geodetic");
  const bool mercator = scheme == tileformat::Scheme::kWebMercator;
  const int steps = pkg.block_size - 1;
  const tileformat::Bounds& b = pkg.meta.common.lonlat;

  // The tiles: a webmercator package's own; a geodetic one's web mercator
  // cover. Geodetic zoom z has samples 180 / (2^z steps) degrees apart, web
  // mercator zoom m pixels 360 / (2^m size) apart at the equator.
  std::vector<ExportTile> plan;
  int min_zoom = pkg.min_zoom, max_zoom = pkg.max_zoom;
  if (mercator) {
    for (int z = pkg.min_zoom; z <= pkg.max_zoom; ++z)
      for (const tileformat::TileId& id : pkg.reader->tile_ids(z))
        plan.push_back({tileformat::pmtiles::tile_id(z, id.x, id.y), z, z, id.x, id.y});
  } else {
    const double finer = std::log2(2.0 * steps / s.tile_size);  // mercator zoom - geodetic zoom
    min_zoom = 0;
    max_zoom = std::clamp(static_cast<int>(std::floor(pkg.max_zoom + finer + 1e-9)), 0, 24);
    for (int m = min_zoom; m <= max_zoom; ++m) {
      const int source = web::raster_dem_source_zoom(pkg, m, s.tile_size);
      tiles_over(b.min_x, b.min_y, b.max_x, b.max_y, m, source, plan);
    }
  }
  std::sort(plan.begin(), plan.end(),
            [](const ExportTile& a, const ExportTile& c) { return a.id < c.id; });

  const std::string ext = "png";
  std::unique_ptr<TileOutput> out = TileOutput::open(s.output, s.force, ext, false);
  const int size = s.tile_size;
  // Tiles come in PMTiles (Hilbert) order: a tile's blocks are mostly its
  // predecessors'; the budget, in blocks, bounds memory whatever the
  // package's size (64 MB of 256-sample blocks).
  web::TerrainBlocks blocks(pkg, 192 * size_t(pkg.block_size) * size_t(pkg.block_size) * 5);
  std::vector<std::unique_ptr<web::TerrainSampler>> samplers;
  for (int t = 0; t < s.threads; ++t)
    samplers.push_back(std::make_unique<web::TerrainSampler>(blocks));
  ExportSummary sum;
  progress.begin("encode tiles", plan.size());
  parallel_batches<NoInputs, EncodedTile>(
      plan.size(), s.threads, 64, [](size_t, size_t) { return NoInputs{}; },
      [&](size_t i, int worker, const NoInputs&) {
        const ExportTile& t = plan[i];
        EncodedTile e;
        e.png = web::raster_dem_tile(*samplers[size_t(worker)], pkg.tiling, t.z, t.x, t.y, size,
                                     t.source_zoom, s.encoding, &e.without_data);
        return e;
      },
      [&](size_t i, EncodedTile&& e) {
        out->put(plan[i].z, plan[i].x, plan[i].y, e.png);
        sum.pixels_without_data += e.without_data;
        progress.advance();
      },
      [](size_t) {});
  progress.end();

  ExportInfo info;
  info.name = std::filesystem::path(s.output).stem().string();
  info.description = std::string("Heights of ") + s.input + " as " +
                     web::encoding_name(s.encoding) +
                     " raster-DEM tiles: each pixel the package's height at the pixel's centre, "
                     "bilinear between the package's samples (which lie on tile edges)";
  info.format = "png";
  info.extension = ext;
  info.tile_type = tileformat::pmtiles::TileType::kPng;
  info.min_zoom = min_zoom, info.max_zoom = max_zoom;
  info.west = b.min_x, info.east = b.max_x;
  info.south = std::max(b.min_y, -kMaxMercatorLat), info.north = std::min(b.max_y, kMaxMercatorLat);
  info.extra_json = std::string("\"encoding\":\"") + web::encoding_name(s.encoding) +
                    "\",\"tileSize\":" + std::to_string(size) +
                    ",\"pixel\":\"area, sampled at its centre\"";
  sum.tiles = out->tiles();
  sum.bytes = out->finish(info);
  sum.min_zoom = min_zoom, sum.max_zoom = max_zoom;
  sum.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return sum;
}

}  // namespace globe
