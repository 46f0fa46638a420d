// `globe-vectorize info`, `validate` and `extract` for line-cluster packages.
// info: metadata, zoom table, and per zoom the segments, points and
// cluster-grid entries (from tile headers only).
// validate decodes every tile (every §7 check of the decoder) and checks the
// package invariants (docs/tileformat.md §7):
//   - extent and grid match the metadata; one reach per zoom;
//   - the cluster grid equals the one recomputed from the segments (§7.3):
//     no segment missing from a cell its footprint touches, none listed in a
//     cell it misses;
//   - every feature id exists in the features table, every class id in
//     globe:classes; tiles lie within minzoom..maxzoom.
// Report on stdout. Exit 0 valid, 5 warnings only, 1 errors.
// extract: the decoded lines and points of one zoom back as vector data in
// the tiling CRS, so OGR tools can check what the package holds. Each run is
// clipped to its own tile's square, so the margins neighbouring tiles share
// appear once.
#include <algorithm>
#include <cstdio>
#include <map>

#include "io/vector_writer.hpp"
#include "kit/kind_inspection.hpp"
#include "kit/package_info.hpp"
#include "kit/validation_report.hpp"
#include "runtime/errors.hpp"
#include "runtime/line_package.hpp"
#include "runtime/package_open.hpp"
#include "tileformat/error.hpp"
#include "tileformat/feature_table.hpp"
#include "tileformat/json.hpp"
#include "tileformat/line_clusters.hpp"
#include "tileformat/line_tile.hpp"
#include "tileformat/shard_table.hpp"

namespace globe {

namespace {

// A bundled-flow package's summary (metadata globe:bundle, tileformat §7.5).
// The parsed globe:bundle; throws InputError if it is not JSON.
tileformat::JsonValue bundle_json(const std::string& json, const std::string& path) {
  try {
    return tileformat::JsonValue::parse(json);
  } catch (const std::exception& e) {
    throw InputError(path + ": metadata globe:bundle is not JSON (" + e.what() +
                     "); rebuild the package (tileformat §7.5)");
  }
}

void print_bundle_info(const std::string& json, const std::string& path) {
  const tileformat::JsonValue b = bundle_json(json, path);
  auto num = [&](const char* key) {
    const tileformat::JsonValue* v = b.find(key);
    return v && v->is_number() ? v->number() : 0.0;
  };
  std::printf("bundled flows:\n");
  std::printf(
      "  connections %.0f: %.0f routed, %.0f unrouted (%.0f beyond --max-snap, %.0f on "
      "one node, %.0f across network components); %.0f bad rows\n",
      num("connections"), num("routed"), num("unrouted"), num("unsnapped"), num("same_node"),
      num("disconnected"), num("bad_rows"));
  std::printf("  bundles %.0f, straight lines %.0f\n", num("bundles"), num("straight_lines"));
  std::printf("  mean detour %.3f (path length / great-circle distance)\n", num("mean_detour"));
  std::printf("  ink ratio %.3f (drawn length / sum of straight lengths)\n", num("ink_ratio"));
  if (b.find("significance"))
    std::printf(
        "  significance %g of the heaviest flow in view: %.0f flows hidden at the coarsest "
        "zoom; --min-weight %g: %.0f never drawn\n",
        num("significance"), num("hidden_at_min_zoom"), num("min_weight"), num("never_drawn"));
  if (const tileformat::JsonValue* n = b.find("network"); n && n->is_object()) {
    auto nn = [&](const char* key) {
      const tileformat::JsonValue* v = n->find(key);
      return v && v->is_number() ? v->number() : 0.0;
    };
    std::printf(
        "  network %.0f nodes, %.0f edges, %.0f components; reduced to %.0f nodes, %.0f "
        "edges\n",
        nn("nodes"), nn("edges"), nn("components"), nn("reduced_nodes"), nn("reduced_edges"));
  }
  if (const tileformat::JsonValue* c = b.find("weight_classes"); c && c->is_array())
    for (const tileformat::JsonValue& k : c->array()) {
      const tileformat::JsonValue *name = k.find("class"), *lo = k.find("min"), *hi = k.find("max");
      if (name && name->is_string() && lo && lo->is_number() && hi && hi->is_number())
        std::printf("  %-10s weight %g .. %g\n", name->string().c_str(), lo->number(),
                    hi->number());
    }
}

int lines_info(const std::string& path, bool json) {
  LinePackage p = open_line_package(path);
  std::map<int, tileformat::LineTileCounts> per_zoom;
  p.file().for_each_tile([&](tileformat::TileId id, std::span<const uint8_t> blob) {
    const auto c = tileformat::peek_line_tile_counts(blob);
    auto& z = per_zoom[id.z];
    z.runs += c.runs;
    z.segments += c.segments;
    z.points += c.points;
    z.cell_entries += c.cell_entries;
  });
  const int64_t features = tileformat::FeatureTableReader(p.file()).count();
  if (json) {
    std::vector<std::string> classes;
    for (const auto& c : p.classes)
      classes.push_back(c.name);
    std::vector<InfoJson> zooms;
    for (const auto& [z, c] : per_zoom)
      zooms.push_back(InfoJson()
                          .integer("zoom", uint64_t(z))
                          .integer("segments", c.segments)
                          .integer("runs", c.runs)
                          .integer("points", c.points)
                          .integer("cell_entries", c.cell_entries));
    InfoJson lines;
    lines.texts("classes", classes)
        .integer("features", uint64_t(features))
        .objects("per_zoom", zooms);
    if (!p.meta.bundle_json.empty()) {
      bundle_json(p.meta.bundle_json, path);  // checked: it is JSON
      lines.raw("bundle", p.meta.bundle_json);
    }
    print_kind_info_json(p.file(), path, tileformat::PackageKind::kLines, lines);
    return kExitOk;
  }
  print_package_info(p.file(), path);
  std::printf("classes:\n");
  for (size_t i = 0; i < p.classes.size(); ++i)
    std::printf("  %4zu %s\n", i, p.classes[i].name.c_str());
  std::printf("features: %lld\n", static_cast<long long>(features));
  if (!p.meta.bundle_json.empty()) print_bundle_info(p.meta.bundle_json, path);
  std::printf("lines per zoom:\n  %4s %12s %12s %10s %14s %10s\n", "zoom", "segments", "runs",
              "points", "cell entries", "per cell");
  const double cells = double(p.cluster_grid) * p.cluster_grid;
  std::map<int, uint64_t> tiles;
  for (const tileformat::ZoomSummary& s : p.file().zoom_summaries())
    tiles[s.zoom] = s.tiles;
  for (const auto& [z, c] : per_zoom)
    std::printf("  %4d %12u %12u %10u %14u %10.2f\n", z, c.segments, c.runs, c.points,
                c.cell_entries, c.cell_entries / (cells * double(tiles[z])));
  return kExitOk;
}

int lines_validate(const std::string& path) {
  LinePackage p = open_line_package(path);
  ValidationReport r;
  tileformat::FeatureTableReader features(p.file());
  const int64_t max_id = features.max_id();
  const int64_t count = features.count();
  // A shard of a sharded build but shard 0 has an empty features table
  // (shard 0 holds it, docs/tileformat.md §10): its tiles' ids are not checked.
  const auto shard =
      read_metadata(path, [&] { return tileformat::read_shard_metadata(p.reader->metadata()); });
  const bool features_in_shard_0 = shard && shard->index != 0 && count == 0;
  if (features_in_shard_0)
    std::printf("%s: shard %d/%d: its features are in shard 0's features table\n", path.c_str(),
                shard->index, shard->count);
  if (count != max_id)
    r.warning("features table ids are not 1.." + std::to_string(count) + " (max id " +
              std::to_string(max_id) + ")");
  std::map<int, uint32_t> reach;
  uint64_t tiles = 0, segments = 0;
  p.file().for_each_tile([&](tileformat::TileId id, std::span<const uint8_t> blob) {
    ++tiles;
    const std::string where = path + " tile " + id.str();
    tileformat::LineTile t;
    try {
      t = tileformat::decode_line_tile(blob);
    } catch (const tileformat::FormatError& e) {
      r.error(where + ": " + e.what());
      return;
    }
    segments += t.segment_count();
    if (id.z < p.min_zoom || id.z > p.max_zoom)
      r.warning(where + ": outside the metadata zoom range " + std::to_string(p.min_zoom) + ".." +
                std::to_string(p.max_zoom));
    if (int(t.extent) != p.extent || int(t.grid) != p.cluster_grid)
      r.error(where + ": extent/grid " + std::to_string(t.extent) + "/" + std::to_string(t.grid) +
              " differ from the metadata (tileformat §7.1)");
    if (auto [it, fresh] = reach.emplace(id.z, t.reach); !fresh && it->second != t.reach)
      r.warning(where + ": reach " + std::to_string(t.reach) +
                " differs from other tiles of zoom " + std::to_string(id.z));
    for (uint64_t f : t.feature_ids)
      if (!features_in_shard_0 && (f < 1 || int64_t(f) > max_id)) {
        r.error(where + ": feature id " + std::to_string(f) + " not in the features table");
        break;
      }
    for (const auto& run : t.runs)
      if (run.class_id >= p.classes.size()) {
        r.error(where + ": class id " + std::to_string(run.class_id) + " not in globe:classes");
        break;
      }
    tileformat::LineTile again = t;
    tileformat::build_cluster_grid(again);
    if (again.cell_offsets != t.cell_offsets || again.cell_segments != t.cell_segments) {
      for (size_t c = 0; c + 1 < t.cell_offsets.size(); ++c) {
        const auto n0 = t.cell_offsets[c + 1] - t.cell_offsets[c];
        const auto n1 = again.cell_offsets[c + 1] - again.cell_offsets[c];
        if (n0 != n1 || !std::equal(t.cell_segments.begin() + t.cell_offsets[c],
                                    t.cell_segments.begin() + t.cell_offsets[c + 1],
                                    again.cell_segments.begin() + again.cell_offsets[c])) {
          r.error(where + ": cluster cell " + std::to_string(c) + " lists " + std::to_string(n0) +
                  " segments, the footprint rule gives " + std::to_string(n1) +
                  " (tileformat §7.3)");
          break;
        }
      }
    }
  });
  std::printf("%s: %llu tiles, %llu segments, %lld features: %llu errors, %llu warnings\n",
              path.c_str(), static_cast<unsigned long long>(tiles),
              static_cast<unsigned long long>(segments), static_cast<long long>(count),
              static_cast<unsigned long long>(r.errors),
              static_cast<unsigned long long>(r.warnings));
  return r.exit_code();
}

int lines_extract(const ExtractRequest& rq) {
  const std::string& path = rq.package;
  const int zoom = rq.zoom;
  LinePackage p = open_line_package(path);
  if (zoom < p.min_zoom || zoom > p.max_zoom)
    throw UsageError("--zoom " + std::to_string(zoom) + ": the package holds zooms " +
                     std::to_string(p.min_zoom) + ".." + std::to_string(p.max_zoom));

  std::map<uint64_t, std::pair<std::string, std::string>> feature_cache;  // layer, properties
  tileformat::FeatureTableReader features(p.file());
  auto feature = [&](uint64_t id) -> const std::pair<std::string, std::string>& {
    auto it = feature_cache.find(id);
    if (it != feature_cache.end()) return it->second;
    std::pair<std::string, std::string> v;
    if (auto f = features.get(static_cast<int64_t>(id))) v = {f->layer, f->properties};
    if (feature_cache.size() > 100000) feature_cache.clear();
    return feature_cache.emplace(id, std::move(v)).first->second;
  };

  VectorWriter out(rq.output,
                   rq.force ? tileformat::IfExists::kOverwrite : tileformat::IfExists::kFail,
                   p.tiling.crs);
  p.file().for_each_tile(
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
      zoom);
  out.commit();
  if (!rq.quiet)
    std::fprintf(stderr, "globe-vectorize: wrote %s: %llu lines, %llu points of zoom %d\n",
                 rq.output.c_str(), static_cast<unsigned long long>(out.lines()),
                 static_cast<unsigned long long>(out.points()), zoom);
  return kExitOk;
}

}  // namespace

// This kind's row of the tool's table (inspect/inspect_commands.cpp).
extern const KindInspection kLinesInspection{tileformat::PackageKind::kLines, lines_info,
                                             lines_validate, lines_extract};

}  // namespace globe
