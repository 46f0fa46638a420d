// `globe-tiler info`, `validate` and `extract` for terrain packages.
// validate decodes every tile and checks the schema and the invariants
// (docs/tileformat.md §3, §5, §6):
//   - shared edge samples and edge split-vertex errors equal in both blocks;
//   - a coarse sample equals the finer sample at the same position;
//   - vertex errors are saturated (>= their children's) within each block.
// Report on stdout. Exit 0 valid, 5 warnings only, 1 errors.
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <optional>

#include "inspect/inspect_commands.hpp"
#include "kit/package_info.hpp"
#include "kit/validation_report.hpp"
#include "runtime/errors.hpp"
#include "runtime/terrain_package.hpp"
#include "tileformat/error.hpp"
#include "tileformat/kpatch.hpp"
#include "tileformat/mblock.hpp"

namespace globe {
namespace {

using tileformat::KPatchLayout;
using tileformat::MBlock;
using tileformat::TileId;

void check_saturation(const KPatchLayout& l, const MBlock& b, const std::string& where,
                      ValidationReport& r) {
  const auto& e = b.vertex_error;
  const int levels = l.depth() / 2;
  // Every vertex's error is at least each of its 4-8 children's (those of
  // this block; the others are checked from their own block).
  auto inside = [](const tileformat::Cell& c) {
    return c.cx >= 0 && c.cy >= 0 && c.cx < (1 << c.m) && c.cy < (1 << c.m);
  };
  auto centre = [&](const tileformat::Cell& c) { return e[l.cell_vertex(c.m, c.cx, c.cy)]; };
  for (int m = 0; m < levels; ++m) {
    const int cells = 1 << m;
    for (int cy = 0; cy < cells; ++cy)
      for (int cx = 0; cx < cells; ++cx)
        for (size_t child : l.centre_children(m, cx, cy))
          if (e[child] > e[l.cell_vertex(m, cx, cy)])
            return r.error(where + ": vertex error not saturated at level " + std::to_string(m));
    for (int row = 0; row <= cells; ++row)
      for (int cx = 0; cx < cells; ++cx)
        for (const tileformat::Cell& c : KPatchLayout::hedge_children(m, row, cx))
          if (inside(c) && centre(c) > e[l.hedge_vertex(m, row, cx)])
            return r.error(where + ": edge vertex error not saturated at level " +
                           std::to_string(m));
    for (int cy = 0; cy < cells; ++cy)
      for (int col = 0; col <= cells; ++col)
        for (const tileformat::Cell& c : KPatchLayout::vedge_children(m, cy, col))
          if (inside(c) && centre(c) > e[l.vedge_vertex(m, cy, col)])
            return r.error(where + ": edge vertex error not saturated at level " +
                           std::to_string(m));
  }
}

int validate_terrain(const std::string& path) {
  TerrainPackage p = open_terrain_package(path);
  ValidationReport r;
  if (p.file().application_id() != tileformat::kApplicationId)
    r.warning("PRAGMA application_id is not 0x4d504258 (tileformat §3.1)");
  for (const char* key : {"name", "bounds", "center", "minzoom", "maxzoom", "type", "version",
                          "description", "globe:format_version", "globe:command_line"})
    if (!p.reader->meta(key))
      r.warning(std::string("metadata key '") + key + "' is missing (tileformat §3.2)");

  std::map<TileId, bool> ids;
  p.file().for_each_tile([&](TileId id, std::span<const uint8_t>) { ids[id] = true; });
  const std::array<KPatchLayout, 2> layouts{KPatchLayout(p.block_size - 1, p.lattice, 0),
                                            KPatchLayout(p.block_size - 1, p.lattice, 1)};
  auto load = [&](TileId id) -> std::optional<MBlock> {
    if (!ids.count(id)) return std::nullopt;
    try {
      return tileformat::decode_mblock(*p.reader->tile(id));
    } catch (const tileformat::FormatError&) {
      return std::nullopt;  // reported once, when the tile itself is checked
    }
  };
  const int n = p.block_size - 1;
  for (const auto& [id, unused] : ids) {
    const std::string where = "tile " + id.str();
    if (!p.tiling.contains(id)) {
      r.error(where + ": outside the tiling's extent");
      continue;
    }
    if (id.z < p.min_zoom || id.z > p.max_zoom) r.error(where + ": zoom outside minzoom..maxzoom");
    MBlock b;
    try {
      b = tileformat::decode_mblock(*p.reader->tile(id));
    } catch (const tileformat::FormatError& e) {
      r.error(where + ": " + e.what());
      continue;
    }
    if (b.size != p.block_size || b.step != p.step_m || b.lattice != p.lattice) {
      r.error(where + ": block size, height step or lattice differ from the metadata");
      continue;
    }
    const KPatchLayout& l = layouts[id.diagonal()];
    check_saturation(l, b, where, r);
    // Shared edges with the east and south neighbours (no wrap-around check).
    for (auto [dx, dy] : {std::pair{1, 0}, std::pair{0, 1}}) {
      const auto nb = load({id.z, id.x + dx, id.y + dy});
      if (!nb) continue;
      for (int i = 0; i <= n; ++i) {
        const int ax = dx ? n : i, ay = dx ? i : n, bx = dx ? 0 : i, by = dx ? i : 0;
        if (b.q[size_t(ay) * b.size + ax] != nb->q[size_t(by) * b.size + bx] ||
            b.is_valid(ax, ay) != nb->is_valid(bx, by)) {
          r.error(where + ": edge sample differs from neighbour " +
                  TileId{id.z, id.x + dx, id.y + dy}.str());
          break;
        }
      }
      for (int m = 0; m < l.depth() / 2; ++m)
        for (int c = 0; c < (1 << m); ++c) {
          const size_t va = dx ? l.vedge_vertex(m, c, 1 << m) : l.hedge_vertex(m, 1 << m, c);
          const size_t vb = dx ? l.vedge_vertex(m, c, 0) : l.hedge_vertex(m, 0, c);
          if (b.vertex_error[va] != nb->vertex_error[vb]) {
            r.error(where + ": shared edge vertex error differs from neighbour " +
                    TileId{id.z, id.x + dx, id.y + dy}.str());
            m = l.depth();
            break;
          }
        }
    }
    // Nested samples: every valid sample of a child equals this block's sample there.
    for (const TileId& c : id.children()) {
      const auto child = load(c);
      if (!child) continue;
      const int ox = (c.x & 1) * n / 2, oy = (c.y & 1) * n / 2;
      bool ok = true;
      for (int y = 0; y <= n && ok; y += 2)
        for (int x = 0; x <= n && ok; x += 2)
          if (child->is_valid(x, y) &&
              (!b.is_valid(ox + x / 2, oy + y / 2) ||
               b.q[size_t(oy + y / 2) * b.size + ox + x / 2] != child->q[size_t(y) * b.size + x]))
            ok = false;
      if (!ok)
        r.error(where + ": a sample differs from child " + c.str() + " at the same position");
    }
  }
  std::printf("%s: %zu tiles checked, %llu errors, %llu warnings\n", path.c_str(), ids.size(),
              static_cast<unsigned long long>(r.errors),
              static_cast<unsigned long long>(r.warnings));
  return r.exit_code();
}

int terrain_info(const std::string& path, bool json) {
  TerrainPackage p = open_terrain_package(path);
  if (json) {
    InfoJson terrain;
    terrain.text("tiling", tileformat::scheme_name(p.tiling.scheme))
        .integer("block_size", uint64_t(p.block_size))
        .integer("kpatch_lattice", uint64_t(p.lattice))
        .number("height_step_m", p.step_m)
        .integer("min_zoom", uint64_t(p.min_zoom))
        .integer("max_zoom", uint64_t(p.max_zoom));
    print_kind_info_json(p.file(), path, tileformat::PackageKind::kTerrain, terrain);
    return kExitOk;
  }
  print_package_info(p.file(), path);
  return kExitOk;
}

int extract_terrain(const ExtractRequest& rq) {
  if (!rq.layer.empty()) throw UsageError("--layer applies to analysis packages only");
  TerrainPackage p = open_terrain_package(rq.package);
  const ExtractTiles t = tiles_to_extract(p.file(), p.tiling, rq, p.min_zoom, p.max_zoom);
  const SampleGrid grid = write_block_samples(
      rq, p.tiling, t, p.block_size, GDT_Float64, [&](TileId id, std::vector<double>& samples) {
        tileformat::MBlock b;
        try {
          b = tileformat::decode_mblock(*p.reader->tile(id));
        } catch (const tileformat::FormatError& e) {
          throw InputError(rq.package + ": tile " + id.str() + ": " + e.what());
        }
        for (int y = 0; y < b.size; ++y)
          for (int x = 0; x < b.size; ++x)
            samples[size_t(y) * b.size + x] =
                b.is_valid(x, y) ? b.height(x, y) : std::numeric_limits<double>::quiet_NaN();
      });
  std::fprintf(stderr, "globe-tiler: wrote %s: %llu x %llu samples from %zu tiles of zoom %d\n",
               rq.output.c_str(), static_cast<unsigned long long>(grid.width),
               static_cast<unsigned long long>(grid.height), t.ids.size(), rq.zoom);
  return kExitOk;
}

}  // namespace

// This kind's row of the tool's table (inspect/inspect_commands.cpp).
extern const KindInspection kTerrainInspection{tileformat::PackageKind::kTerrain, terrain_info,
                                               validate_terrain, extract_terrain};

}  // namespace globe
