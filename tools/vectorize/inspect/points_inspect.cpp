// `globe-vectorize info | validate | extract` of a point package (docs/points.md):
// the rows of inspect_commands.cpp's table for point packages.
//  - info: metadata, fields, per zoom the tiles, places, aggregates and
//    cluster-grid entries (tile headers, and the places' counts);
//  - validate: decodes every tile (every §11 check of the decoder) and
//    checks the package invariants: extent, grid and field count match the
//    metadata, one reach per zoom, the cluster grid equals the recomputed
//    one (§11.3), ids are in the features table and unique within a zoom,
//    every zoom stands for every source place exactly once (its counts sum
//    to globe:features), each zoom's places and largest values agree with
//    globe:zoom_stats, and with --aggregate sum every zoom's totals equal
//    the finest zoom's (values are float32: within 1e-5 relative).
//  - extract: one zoom's places as points in the tiling CRS, with their id,
//    count, tile, properties and one field per value.
#include <cmath>
#include <cstdio>
#include <map>

#include "io/vector_writer.hpp"
#include "kit/kind_inspection.hpp"
#include "kit/package_info.hpp"
#include "kit/validation_report.hpp"
#include "runtime/errors.hpp"
#include "runtime/point_package.hpp"
#include "tileformat/error.hpp"
#include "tileformat/feature_table.hpp"
#include "tileformat/point_tile.hpp"

namespace globe {

namespace {

struct ZoomTotals {
  uint64_t tiles = 0, places = 0, aggregates = 0, sources = 0, cell_entries = 0;
  double max_total = 0, max_value = 0;
  std::vector<double> sums;  // per field
};

// Per zoom: tiles, places, merged places, the places they stand for and cell
// entries, from every tile.
std::map<int, ZoomTotals> zoom_totals(PointPackage& p) {
  std::map<int, ZoomTotals> zooms;
  p.file().for_each_tile([&](tileformat::TileId id, std::span<const uint8_t> blob) {
    const tileformat::PointTile t = tileformat::decode_point_tile(blob);
    ZoomTotals& z = zooms[id.z];
    ++z.tiles;
    z.places += t.places.size();
    z.cell_entries += t.cell_places.size();
    for (const tileformat::Place& pl : t.places) {
      z.aggregates += pl.count > 1;
      z.sources += pl.count;
    }
  });
  return zooms;
}

int points_info(const std::string& path, bool json) {
  PointPackage p = open_point_package(path);
  const tileformat::PointMetadata& m = p.meta;
  if (json) {
    std::vector<InfoJson> per_zoom;
    for (const auto& [z, t] : zoom_totals(p))
      per_zoom.push_back(InfoJson()
                             .integer("zoom", uint64_t(z))
                             .integer("tiles", t.tiles)
                             .integer("places", t.places)
                             .integer("merged", t.aggregates)
                             .integer("stand_for", t.sources)
                             .integer("cell_entries", t.cell_entries));
    InfoJson points;
    points.texts("fields", m.fields)
        .text("aggregate", m.aggregate == tileformat::PointAggregate::kSum ? "sum" : "mean")
        .number("merge_px", m.merge_px)
        .boolean("signed", m.signed_values)
        .text("label_field", m.label_field)
        .integer("places", m.features)
        .objects("per_zoom", per_zoom);
    print_kind_info_json(p.file(), path, tileformat::PackageKind::kPoints, points);
    return kExitOk;
  }
  print_package_info(p.file(), path);
  std::printf("fields:");
  for (const std::string& f : m.fields)
    std::printf(" %s", f.c_str());
  std::printf("\naggregate: %s of places within %g px; values %s; label field: %s\n",
              m.aggregate == tileformat::PointAggregate::kSum ? "sum" : "mean", m.merge_px,
              m.signed_values ? "signed" : "non-negative",
              m.label_field.empty() ? "(none)" : m.label_field.c_str());
  std::printf("source places: %llu\n", static_cast<unsigned long long>(m.features));
  const std::map<int, ZoomTotals> zooms = zoom_totals(p);
  std::printf("places per zoom:\n  %4s %8s %10s %10s %12s %14s\n", "zoom", "tiles", "places",
              "merged", "stand for", "cell entries");
  for (const auto& [z, t] : zooms)
    std::printf("  %4d %8llu %10llu %10llu %12llu %14llu\n", z,
                static_cast<unsigned long long>(t.tiles), static_cast<unsigned long long>(t.places),
                static_cast<unsigned long long>(t.aggregates),
                static_cast<unsigned long long>(t.sources),
                static_cast<unsigned long long>(t.cell_entries));
  return kExitOk;
}

int points_validate(const std::string& path) {
  PointPackage p = open_point_package(path);
  const tileformat::PointMetadata& m = p.meta;
  ValidationReport r;
  tileformat::FeatureTableReader features(p.file());
  const int64_t max_id = features.max_id();
  if (features.count() != max_id || uint64_t(max_id) != m.features)
    r.warning("features table ids are not 1.." + std::to_string(m.features) + " (" +
              std::to_string(features.count()) + " rows, max id " + std::to_string(max_id) + ")");
  const size_t nfields = m.fields.size();
  std::map<int, ZoomTotals> zooms;
  std::map<int, std::vector<uint8_t>> seen;  // per zoom: whether an id was met
  std::map<int, uint32_t> reach;
  p.file().for_each_tile([&](tileformat::TileId id, std::span<const uint8_t> blob) {
    const std::string where = path + " tile " + id.str();
    tileformat::PointTile t;
    try {
      t = tileformat::decode_point_tile(blob);
    } catch (const tileformat::FormatError& e) {
      r.error(where + ": " + e.what());
      return;
    }
    if (id.z < m.common.min_zoom || id.z > m.common.max_zoom)
      r.warning(where + ": outside the metadata zoom range");
    if (int(t.extent) != m.extent || int(t.grid) != m.cluster_grid || t.fields != nfields)
      r.error(where + ": extent/grid/fields " + std::to_string(t.extent) + "/" +
              std::to_string(t.grid) + "/" + std::to_string(t.fields) +
              " differ from the metadata (tileformat §11.1)");
    if (auto [it, fresh] = reach.emplace(id.z, t.reach); !fresh && it->second != t.reach)
      r.warning(where + ": reach differs from other tiles of zoom " + std::to_string(id.z));
    tileformat::PointTile again = t;
    tileformat::build_point_grid(again);
    if (again.cell_offsets != t.cell_offsets || again.cell_places != t.cell_places)
      r.error(where + ": the cluster grid is not the one the §11.3 rule gives");
    ZoomTotals& z = zooms[id.z];
    z.sums.resize(nfields, 0.0);
    for (size_t i = 0; i < t.places.size(); ++i) {
      const tileformat::Place& pl = t.places[i];
      if (pl.id < 1 || int64_t(pl.id) > max_id) {
        r.error(where + ": place id " + std::to_string(pl.id) + " not in the features table");
      } else {
        std::vector<uint8_t>& met = seen[id.z];
        met.resize(size_t(max_id) + 1, 0);
        if (met[pl.id]++)
          r.error(where + ": place id " + std::to_string(pl.id) + " twice at zoom " +
                  std::to_string(id.z));
      }
      ++z.places;
      z.sources += pl.count;
      double total = 0;
      for (uint32_t f = 0; f < t.fields && f < nfields; ++f) {
        const double v = t.value(i, f);
        if (!std::isfinite(v)) r.error(where + ": a value is not a finite number");
        if (v < 0 && !m.signed_values)
          r.error(where + ": a negative value in a package marked non-negative");
        // The sums of what the places stand for (means times their counts).
        z.sums[f] += m.aggregate == tileformat::PointAggregate::kSum ? v : v * pl.count;
        total += std::abs(v);
        z.max_value = std::max(z.max_value, std::abs(v));
      }
      z.max_total = std::max(z.max_total, total);
    }
  });
  const ZoomTotals* finest = zooms.empty() ? nullptr : &zooms.rbegin()->second;
  for (const auto& [zoom, z] : zooms) {
    const std::string where = path + " zoom " + std::to_string(zoom);
    if (z.sources != m.features)
      r.error(where + ": places stand for " + std::to_string(z.sources) + " source places, not " +
              std::to_string(m.features) + " (each once per zoom)");
    for (size_t f = 0; f < nfields; ++f)
      if (std::abs(z.sums[f] - finest->sums[f]) > 1e-5 * std::max(1.0, std::abs(finest->sums[f])))
        r.error(where + ": the total of " + m.fields[f] + " is " + std::to_string(z.sums[f]) +
                ", the finest zoom's " + std::to_string(finest->sums[f]) + " (not conserved)");
    bool listed = false;
    for (const tileformat::PointZoomStats& s : m.zooms) {
      if (s.zoom != zoom) continue;
      listed = true;
      if (s.places != z.places || std::abs(s.max_total - z.max_total) > 1e-5 * s.max_total ||
          std::abs(s.max_value - z.max_value) > 1e-5 * s.max_value)
        r.error(where + ": globe:zoom_stats says " + std::to_string(s.places) +
                " places (largest total " + std::to_string(s.max_total) + "), the tiles hold " +
                std::to_string(z.places) + " (" + std::to_string(z.max_total) + ")");
    }
    if (!listed) r.warning(where + ": not in globe:zoom_stats");
  }
  uint64_t tiles = 0, places = 0;
  for (const auto& [zoom, z] : zooms)
    places += z.places;
  for (const tileformat::ZoomSummary& s : p.file().zoom_summaries())
    tiles += s.tiles;
  std::printf("%s: %llu tiles, %llu places, %lld source places: %llu errors, %llu warnings\n",
              path.c_str(), static_cast<unsigned long long>(tiles),
              static_cast<unsigned long long>(places), static_cast<long long>(m.features),
              static_cast<unsigned long long>(r.errors),
              static_cast<unsigned long long>(r.warnings));
  return r.exit_code();
}

int points_extract(const ExtractRequest& rq) {
  const std::string& path = rq.package;
  const int zoom = rq.zoom;
  PointPackage p = open_point_package(path);
  if (zoom < p.meta.common.min_zoom || zoom > p.meta.common.max_zoom)
    throw UsageError("--zoom " + std::to_string(zoom) + ": the package holds zooms " +
                     std::to_string(p.meta.common.min_zoom) + ".." +
                     std::to_string(p.meta.common.max_zoom));
  std::vector<std::string> names;
  for (const std::string& f : p.meta.fields)
    names.push_back(
        f == "place_id" || f == "places" || f == "tile" || f == "properties" ? f + "_value" : f);
  VectorWriter out(rq.output,
                   rq.force ? tileformat::IfExists::kOverwrite : tileformat::IfExists::kFail,
                   p.meta.common.tiling.crs);
  out.set_value_fields(names);
  tileformat::FeatureTableReader features(p.file());
  const tileformat::Tiling& tiling = p.meta.common.tiling;
  uint64_t n = 0;
  p.file().for_each_tile(
      [&](tileformat::TileId id, std::span<const uint8_t> blob) {
        const tileformat::PointTile t = tileformat::decode_point_tile(blob);
        const tileformat::Bounds b = tiling.tile_bounds(id);
        const double unit = b.width() / t.extent;
        for (size_t i = 0; i < t.places.size(); ++i) {
          const tileformat::Place& pl = t.places[i];
          PlaceAttributes a;
          a.place_id = static_cast<int64_t>(pl.id);
          a.places = pl.count;
          a.tile = id.str();
          // An aggregate has no attributes of its own.
          if (pl.count == 1)
            if (auto f = features.get(static_cast<int64_t>(pl.id))) a.properties = f->properties;
          for (uint32_t f = 0; f < t.fields; ++f)
            a.values.push_back(t.value(i, f));
          out.add_place({b.min_x + pl.at.x * unit, b.max_y - pl.at.y * unit}, a);
          ++n;
        }
      },
      zoom);
  out.commit();
  if (!rq.quiet)
    std::fprintf(stderr, "globe-vectorize: wrote %s: %llu places of zoom %d\n", rq.output.c_str(),
                 static_cast<unsigned long long>(n), zoom);
  return kExitOk;
}

}  // namespace

// This kind's row of the tool's table (inspect/inspect_commands.cpp).
extern const KindInspection kPointsInspection{tileformat::PackageKind::kPoints, points_info,
                                              points_validate, points_extract};

}  // namespace globe
