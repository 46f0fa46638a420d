// Quantized-mesh export (see mesh_export.hpp).
#include "mesh_export.hpp"

#include <array>
#include <chrono>
#include <filesystem>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <unordered_map>
#include <vector>

#include "errors.hpp"
#include "gzip.hpp"
#include "mesh_tiles.hpp"
#include "parallel_batches.hpp"
#include "terrain_package.hpp"
#include "tile_output.hpp"

namespace globe {
namespace {

using tileformat::TileId;

uint64_t key(int z, uint64_t x, uint64_t y) {
  return uint64_t(z) << 58 | x << 29 | y;
}

// Edge halves of one tile, in TileEdge order (north, east, south, west).
using Halves = std::array<std::vector<float>, 4>;

}  // namespace

ExportSummary export_quantized_mesh(const MeshExportSettings& s, Progress& progress) {
  const auto start = std::chrono::steady_clock::now();
  TerrainPackage pkg = open_terrain_package(s.input);
  const tileformat::Tiling& tiling = pkg.tiling;
  if (tiling.scheme == tileformat::Scheme::kLocal)
    throw UsageError(s.input +
                     ": a package in a local tiling has no CesiumJS tiling scheme; build it with "
                     "--tiling geodetic (Cesium's default EPSG:4326) or webmercator");
  if (output_kind(s.output) == OutputKind::kPmtiles)
    throw UsageError(s.output +
                     ": CesiumJS reads quantized-mesh from a folder with layer.json (or a server); "
                     "give -o DIR or -o OUT.mbtiles");

  const std::vector<std::vector<TileId>> plan = web::mesh_tile_plan(pkg);
  std::vector<TileId> tiles;
  for (const std::vector<TileId>& level : plan)
    tiles.insert(tiles.end(), level.begin(), level.end());
  std::unordered_map<uint64_t, size_t> index;
  for (size_t i = 0; i < tiles.size(); ++i)
    index[key(tiles[i].z, tiles[i].x, tiles[i].y)] = i;

  std::mutex read_mutex;
  std::vector<std::unique_ptr<web::MeshTileSource>> sources;
  for (int t = 0; t < s.threads; ++t)
    sources.push_back(std::make_unique<web::MeshTileSource>(pkg, read_mutex));

  // A tile's errors: its own triangles', its edges raised to its
  // neighbours' values of the previous pass (none in the first).
  auto tile_errors = [&](size_t i, const web::TileGrid& grid, const std::vector<Halves>& edges) {
    const TileId id = tiles[i];
    web::MeshErrors errors(grid, web::mesh_sample_metres(tiling, id.z, grid.steps));
    if (edges.empty()) return errors;
    const int64_t cols = int64_t(tiling.tiles_x(id.z)), rows = int64_t(tiling.tiles_y(id.z));
    // The neighbour across each edge and the edge of its that is shared.
    const struct {
      web::TileEdge edge, theirs;
      int64_t dx, dy;
    } sides[4] = {{web::TileEdge::kNorth, web::TileEdge::kSouth, 0, -1},
                  {web::TileEdge::kEast, web::TileEdge::kWest, 1, 0},
                  {web::TileEdge::kSouth, web::TileEdge::kNorth, 0, 1},
                  {web::TileEdge::kWest, web::TileEdge::kEast, -1, 0}};
    for (const auto& side : sides) {
      int64_t x = int64_t(id.x) + side.dx, y = int64_t(id.y) + side.dy;
      if (tiling.wraps_x()) x = (x % cols + cols) % cols;
      if (x < 0 || y < 0 || x >= cols || y >= rows) continue;
      const auto it = index.find(key(id.z, uint64_t(x), uint64_t(y)));
      if (it != index.end()) errors.join_neighbour(side.edge, edges[it->second][int(side.theirs)]);
    }
    errors.finish();
    return errors;
  };

  // The edges' errors, exchanged between neighbours until they agree: an edge
  // vertex's descendants reach into the tiles beside both its tiles, so one
  // exchange is not always enough (2 to 4 passes on the tests and benchmarks).
  std::vector<Halves> edges;
  constexpr int kMaxPasses = 12;
  int pass = 1;
  for (;; ++pass) {
    std::vector<Halves> next(tiles.size());
    progress.begin("edge errors, pass " + std::to_string(pass), tiles.size());
    parallel_batches<NoInputs, Halves>(
        tiles.size(), s.threads, 16, [](size_t, size_t) { return NoInputs{}; },
        [&](size_t i, int worker, const NoInputs&) {
          const web::TileGrid grid = sources[size_t(worker)]->grid(tiles[i]);
          const web::MeshErrors errors = tile_errors(i, grid, edges);
          Halves h;
          for (int e = 0; e < 4; ++e)
            h[e] = errors.edge_halves(web::TileEdge(e));
          return h;
        },
        [&](size_t i, Halves&& h) {
          next[i] = std::move(h);
          progress.advance();
        },
        [](size_t) {});
    progress.end();
    const bool settled = next == edges;
    edges = std::move(next);
    if (settled) break;
    if (pass == kMaxPasses)
      throw std::runtime_error(s.input + ": the tiles' edge errors did not settle in " +
                               std::to_string(kMaxPasses) + " passes; please report this");
  }

  // Each tile cut with the settled edges.
  std::unique_ptr<TileOutput> out = TileOutput::open(s.output, s.force, "terrain", true);
  web::MeshTileOptions options;
  options.normals = s.normals;
  options.error_scale = s.error_scale;
  options.finest_zoom = pkg.max_zoom;
  options.finest_error = s.finest_error;
  progress.begin("encode tiles", tiles.size());
  parallel_batches<NoInputs, std::vector<uint8_t>>(
      tiles.size(), s.threads, 16, [](size_t, size_t) { return NoInputs{}; },
      [&](size_t i, int worker, const NoInputs&) {
        const web::TileGrid grid = sources[size_t(worker)]->grid(tiles[i]);
        const web::MeshErrors errors = tile_errors(i, grid, edges);
        std::vector<uint8_t> bytes = web::encode_mesh_tile(tiling, tiles[i], grid, errors, options);
        return s.gzip ? web::gzip(bytes, 6) : bytes;
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
  info.side_files.push_back(
      {"layer.json", web::layer_json(pkg, plan, info.name, info.description, s.normals)});
  if (s.gzip) info.extra_json = "\"content_encoding\":\"gzip\"";
  ExportSummary sum;
  sum.tiles = out->tiles();
  sum.bytes = out->finish(info);
  sum.min_zoom = info.min_zoom, sum.max_zoom = info.max_zoom;
  sum.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return sum;
}

}  // namespace globe
