// `globe-vectorize extract PACKAGE --zoom Z -o OUT.gpkg`: the decoded lines
// and points of one zoom back as vector data in the tiling CRS, so OGR tools
// can check what the package holds. Each run is clipped to its own tile's
// square, so the margins neighbouring tiles share appear once.
#include <cstdio>
#include <map>

#include "inspect/points_inspect.hpp"
#include "io/vector_writer.hpp"
#include "runtime/cli_args.hpp"
#include "runtime/errors.hpp"
#include "runtime/line_package.hpp"
#include "runtime/package_open.hpp"
#include "runtime/point_package.hpp"
#include "tileformat/feature_table.hpp"
#include "tileformat/line_tile.hpp"
#include "vectorize_commands.hpp"

namespace globe {

int run_lines_extract(const std::vector<std::string>& args) {
  std::optional<int> zoom;
  std::string output;
  bool force = false, quiet = false;
  CliArgs cli("globe-vectorize extract",
              "globe-vectorize extract PACKAGE --zoom Z -o OUT.gpkg\n\n"
              "Writes the lines (and points) of zoom Z, clipped to their tiles, as vector data\n"
              "(GeoPackage; .geojson, .shp, .fgb by extension) in the tiling CRS. Of a point\n"
              "package: its places with their values (layer places).");
  cli.option("--zoom", "Z", "zoom level to extract",
             [&](const std::string& v) { zoom = CliArgs::to_int("--zoom", v, 0, 30); });
  cli.option("-o,--output", "OUT.gpkg", "output file", [&](const std::string& v) { output = v; });
  cli.flag("--force", "replace an existing output", [&] { force = true; });
  cli.flag("-q,--quiet", "no summary on stderr", [&] { quiet = true; });
  auto positional = cli.parse_command(args, 1, 1, "PACKAGE");
  if (!positional) return kExitOk;
  if (!zoom) throw UsageError("--zoom is required");
  if (output.empty()) throw UsageError("no output given; add -o OUT.gpkg");
  const std::string& path = (*positional)[0];
  if (package_kind(path) == tileformat::PackageKind::kPoints) {
    const PointPackage points = open_point_package(path);
    VectorWriter out(output, force ? tileformat::IfExists::kOverwrite : tileformat::IfExists::kFail,
                     points.meta.common.tiling.crs);
    const uint64_t n = points_extract(path, *zoom, out);
    out.commit();
    if (!quiet)
      std::fprintf(stderr, "globe-vectorize: wrote %s: %llu places of zoom %d\n", output.c_str(),
                   static_cast<unsigned long long>(n), *zoom);
    return kExitOk;
  }
  LinePackage p = open_line_package(path);
  if (*zoom < p.min_zoom || *zoom > p.max_zoom)
    throw UsageError("--zoom " + std::to_string(*zoom) + ": the package holds zooms " +
                     std::to_string(p.min_zoom) + ".." + std::to_string(p.max_zoom));

  std::map<uint64_t, std::pair<std::string, std::string>> feature_cache;  // layer, properties
  tileformat::FeatureTableReader features(*p.reader);
  auto feature = [&](uint64_t id) -> const std::pair<std::string, std::string>& {
    auto it = feature_cache.find(id);
    if (it != feature_cache.end()) return it->second;
    std::pair<std::string, std::string> v;
    if (auto f = features.get(static_cast<int64_t>(id))) v = {f->layer, f->properties};
    if (feature_cache.size() > 100000) feature_cache.clear();
    return feature_cache.emplace(id, std::move(v)).first->second;
  };

  VectorWriter out(output, force ? tileformat::IfExists::kOverwrite : tileformat::IfExists::kFail,
                   p.tiling.crs);
  p.reader->for_each_tile(
      [&](tileformat::TileId id, std::span<const uint8_t> blob) {
        const tileformat::LineTile t = tileformat::decode_line_tile(blob);
        const tileformat::Bounds b = p.tiling.tile_bounds(id);
        const double scale = b.width() / t.extent;
        auto to_crs = [&](XY u) { return XY{b.min_x + u.x * scale, b.max_y - u.y * scale}; };
        const tileformat::Bounds square{0, 0, double(t.extent), double(t.extent)};
        auto attributes = [&](uint32_t feature_index, uint32_t class_id) {
          const uint64_t fid = t.feature_ids[feature_index];
          const auto& [layer, props] = feature(fid);
          return VectorAttributes{static_cast<int64_t>(fid),
                                  class_id < p.classes.size() ? p.classes[class_id].name : "",
                                  layer, id.str(), props};
        };
        for (const auto& run : t.runs) {
          const VectorAttributes a = attributes(run.feature, run.class_id);
          std::vector<XY> piece;
          for (uint32_t i = 0; i + 1 < run.vertex_count; ++i) {
            const auto& va = t.vertices[run.first_vertex + i];
            const auto& vb = t.vertices[run.first_vertex + i + 1];
            XY c{double(va.x), double(va.y)}, d{double(vb.x), double(vb.y)};
            double t0 = 0, t1 = 1;
            if (!clip_segment(c, d, square, &t0, &t1)) continue;
            if (t0 > 0 || piece.empty()) {
              if (piece.size() >= 2) out.add_line(piece, a);
              piece = {to_crs(c)};
            }
            piece.push_back(to_crs(d));
            if (t1 < 1) {
              out.add_line(piece, a);
              piece.clear();
            }
          }
          if (piece.size() >= 2) out.add_line(piece, a);
        }
        for (const auto& pt : t.points) {
          if (pt.at.x < 0 || pt.at.y < 0 || pt.at.x > int(t.extent) || pt.at.y > int(t.extent))
            continue;
          out.add_point(to_crs({double(pt.at.x), double(pt.at.y)}),
                        attributes(pt.feature, pt.class_id));
        }
      },
      *zoom);
  out.commit();
  if (!quiet)
    std::fprintf(stderr, "globe-vectorize: wrote %s: %llu lines, %llu points of zoom %d\n",
                 output.c_str(), static_cast<unsigned long long>(out.lines()),
                 static_cast<unsigned long long>(out.points()), *zoom);
  return kExitOk;
}

}  // namespace globe
