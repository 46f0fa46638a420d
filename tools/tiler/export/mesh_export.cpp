// Quantized-mesh export (see mesh_export.hpp).
#include "export/mesh_export.hpp"

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <memory>
#include <vector>

#include "kit/parallel_batches.hpp"
#include "runtime/errors.hpp"
#include "runtime/terrain_package.hpp"
#include "tileformat/pmtiles.hpp"
#include "web/gzip.hpp"
#include "web/mesh_tiles.hpp"
#include "web/tile_output.hpp"

namespace globe {

using tileformat::TileId;

std::function<WaterMask(const std::string& path)>& water_mask_factory() {
  static std::function<WaterMask(const std::string&)> factory;
  return factory;
}

ExportSummary export_quantized_mesh(const MeshExportSettings& s, Progress& progress) {
  const auto start = std::chrono::steady_clock::now();
  TerrainPackage pkg = open_terrain_package(s.input);
  pkg.file().stream();  // one pass: no mapped pages held (PackageReader::stream)
  const tileformat::Tiling& tiling = pkg.tiling;
  if (tiling.scheme == tileformat::Scheme::kLocal)
    throw UsageError(s.input +
                     ": a package in a local tiling has no CesiumJS tiling scheme; build it with "
                     "--tiling geodetic (Cesium's default EPSG:4326) or webmercator");
  if (output_kind(s.output) == OutputKind::kPmtiles)
    throw UsageError(s.output +
                     ": CesiumJS reads quantized-mesh from a folder with layer.json (or a server); "
                     "give -o DIR or -o OUT.mbtiles");

  // Opened first: an existing output is refused before any work is done.
  std::unique_ptr<TileOutput> out = TileOutput::open(s.output, s.force, "terrain", true);
  const std::vector<std::vector<TileId>> plan = web::mesh_tile_plan(pkg);
  std::vector<TileId> tiles;
  for (const std::vector<TileId>& level : plan)
    tiles.insert(tiles.end(), level.begin(), level.end());
  // Along the Hilbert curve of each zoom, so that a worker's next tiles are
  // its last ones' neighbours (their own errors are still cached). A
  // geodetic zoom's 2^(z+1) x 2^z tiles lie in web mercator zoom z + 1's square.
  const int wide = tiling.roots_x > 1 ? 1 : 0;
  auto order = [&](const TileId& t) { return tileformat::pmtiles::tile_id(t.z + wide, t.x, t.y); };
  std::sort(tiles.begin(), tiles.end(),
            [&](const TileId& a, const TileId& b) { return order(a) < order(b); });

  // The workers share the decoded blocks and each tile's own errors (a tile's
  // are needed by its eight neighbours too), within budgets counted in tiles,
  // not bytes: what the Hilbert order needs is a number of neighbours, and
  // memory stays flat whatever the package's size (bench/README.md
  // "Exports"). 256-sample blocks: 64 MB of blocks, 192 MB of errors.
  const size_t samples = size_t(pkg.block_size) * size_t(pkg.block_size);
  web::TerrainBlocks blocks(pkg, 192 * samples * 5);  // heights, validity
  web::OwnErrorCache own_errors(720 * samples * sizeof(float));
  std::vector<std::unique_ptr<web::MeshTileSource>> sources;
  for (int t = 0; t < s.threads; ++t)
    sources.push_back(std::make_unique<web::MeshTileSource>(blocks, own_errors));

  // Each tile alone: its errors from the blocks of it and its neighbours.
  web::MeshTileOptions options;
  options.normals = s.normals;
  options.error_scale = s.error_scale;
  options.finest_zoom = pkg.max_zoom;
  options.finest_error = s.finest_error;
  if (!s.watermask.empty()) {
    if (!water_mask_factory())
      throw UsageError("--watermask needs globe-tiler-gdal (run the export through globe-tiler)");
    options.water_mask = water_mask_factory()(s.watermask);
  }
  progress.begin("encode tiles", tiles.size());
  parallel_batches<NoInputs, std::vector<uint8_t>>(
      tiles.size(), s.threads, 16, [](size_t, size_t) { return NoInputs{}; },
      [&](size_t i, int worker, const NoInputs&) {
        web::MeshTileSource& source = *sources[size_t(worker)];
        const web::TileGrid grid = source.grid(tiles[i]);
        const web::MeshErrors errors =
            source.errors(tiles[i], options.threshold(tiles[i].z, tiling.roots_x));
        std::vector<uint8_t> bytes = web::encode_mesh_tile(tiling, tiles[i], grid, errors, options);
        return s.gzip ? web::gzip(bytes, s.gzip_level) : bytes;
      },
      [&](size_t i, std::vector<uint8_t>&& bytes) {
        out->put(tiles[i].z, tiles[i].x, tiles[i].y, bytes);
        progress.advance();
      },
      [](size_t) {});
  progress.end();

  const tileformat::Bounds& b = pkg.meta.common.lonlat;
  ExportInfo info;
  info.name = std::filesystem::path(s.output).stem().string();
  info.description = "Heights of " + s.input +
                     " as quantized-mesh-1.0: per tile a TIN within CesiumJS's geometric error "
                     "of its level, cut from the package's samples";
  info.format = "quantized-mesh-1.0";
  info.extension = "terrain";
  info.min_zoom = 0, info.max_zoom = int(plan.size()) - 1;
  info.west = b.min_x, info.east = b.max_x, info.south = b.min_y, info.north = b.max_y;
  info.tms_rows = true;
  info.side_files.push_back({"layer.json", web::layer_json(pkg, plan, info.name, info.description,
                                                           s.normals, !s.watermask.empty())});
  if (s.gzip) info.extra_json = "\"content_encoding\":\"gzip\"";
  ExportSummary sum;
  sum.tiles = out->tiles();
  sum.bytes = out->finish(info);
  sum.min_zoom = info.min_zoom, sum.max_zoom = info.max_zoom;
  sum.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return sum;
}

}  // namespace globe
