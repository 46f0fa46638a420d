// `globe-vectorize info | validate | extract` of an area package
// (docs/areas.md): the rows of inspect_commands.cpp's table for area packages.
//  - info: metadata, classes or the choropleth's classes, per zoom the
//    tiles, polygons, rings and vertices (from tile headers only);
//  - validate: decodes every tile (every §12 check of the decoder:
//    orientation, vertices within the buffer) and checks the package
//    invariants: extent and buffer match the metadata, feature ids are in
//    the features table, class ids in globe:classes or the choropleth, and
//    every tile's polygons are valid (GEOS);
//  - extract: one zoom's polygons clipped to their own tiles (so the buffers
//    neighbours share appear once), in the tiling CRS.
#include <cstdio>
#include <map>

#include "geo/geos_polygons.hpp"
#include "io/vector_writer.hpp"
#include "kit/kind_inspection.hpp"
#include "kit/package_info.hpp"
#include "kit/validation_report.hpp"
#include "runtime/area_package.hpp"
#include "runtime/errors.hpp"
#include "tileformat/area_tile.hpp"
#include "tileformat/error.hpp"
#include "tileformat/feature_table.hpp"

namespace globe {

namespace {

struct ZoomCounts {
  uint64_t tiles = 0, polygons = 0, rings = 0, vertices = 0;
};

std::map<int, ZoomCounts> zoom_counts(AreaPackage& p) {
  std::map<int, ZoomCounts> zooms;
  p.file().for_each_tile([&](tileformat::TileId id, std::span<const uint8_t> blob) {
    const tileformat::AreaTileCounts c = tileformat::peek_area_tile_counts(blob);
    ZoomCounts& z = zooms[id.z];
    ++z.tiles;
    z.polygons += c.polygons;
    z.rings += c.rings;
    z.vertices += c.vertices;
  });
  return zooms;
}

// The tile's polygons, each as rings of tile units (for GEOS and extract).
std::vector<std::pair<uint32_t, PlanePolygon>> tile_polygons(const tileformat::AreaTile& t) {
  std::vector<std::pair<uint32_t, PlanePolygon>> out;
  const std::vector<uint32_t> offsets = t.ring_offsets();
  for (const tileformat::AreaPolygon& a : t.polygons) {
    PlanePolygon p;
    for (uint32_t r = a.first_ring; r < a.first_ring + a.ring_count; ++r) {
      p.emplace_back();
      for (uint32_t v = offsets[r]; v < offsets[r + 1]; ++v)
        p.back().push_back({double(t.vertices[v].x), double(t.vertices[v].y)});
    }
    out.emplace_back(static_cast<uint32_t>(&a - t.polygons.data()), std::move(p));
  }
  return out;
}

int areas_info(const std::string& path, bool json) {
  AreaPackage p = open_area_package(path);
  const tileformat::AreaMetadata& m = p.meta;
  const std::map<int, ZoomCounts> zooms = zoom_counts(p);
  if (json) {
    std::vector<InfoJson> per_zoom;
    for (const auto& [z, c] : zooms)
      per_zoom.push_back(InfoJson()
                             .integer("zoom", uint64_t(z))
                             .integer("tiles", c.tiles)
                             .integer("polygons", c.polygons)
                             .integer("rings", c.rings)
                             .integer("vertices", c.vertices));
    InfoJson areas;
    areas.integer("features", m.features)
        .integer("extent", uint64_t(m.extent))
        .integer("buffer", uint64_t(m.buffer))
        .number("simplify_px", m.simplify_px)
        .integer("repaired", m.repaired)
        .raw("style_classes", m.classes_json.empty() ? "[]" : m.classes_json);
    if (const auto& c = m.choropleth) {
      std::vector<InfoJson> classes;
      for (const tileformat::ChoroplethClass& k : c->classes)
        classes.push_back(
            InfoJson().number("min", k.min).number("max", k.max).text("color", k.color));
      areas.objects("classes", classes);
      areas.object("choropleth", InfoJson()
                                     .text("field", c->field)
                                     .text("denominator", c->denominator)
                                     .text("method", c->method)
                                     .text("ramp", c->ramp)
                                     .text("no_data_color", c->no_data_color)
                                     .integer("no_data", c->no_data));
    }
    areas.objects("per_zoom", per_zoom);
    print_kind_info_json(p.file(), path, tileformat::PackageKind::kAreas, areas);
    return kExitOk;
  }
  print_package_info(p.file(), path);
  std::printf("features: %llu (%llu repaired by MakeValid)\n",
              static_cast<unsigned long long>(m.features),
              static_cast<unsigned long long>(m.repaired));
  std::printf("snapping grid %g px a zoom (the finest: 1 unit), buffer %d units of %d\n",
              m.simplify_px, m.buffer, m.extent);
  if (const auto& c = m.choropleth) {
    std::printf("choropleth: %s%s%s, %s breaks, ColorBrewer %s\n", c->field.c_str(),
                c->denominator.empty() ? "" : " / ", c->denominator.c_str(), c->method.c_str(),
                c->ramp.c_str());
    for (size_t i = 0; i < c->classes.size(); ++i)
      std::printf("  class %zu  %s  %.6g .. %.6g%s\n", i + 1, c->classes[i].color.c_str(),
                  c->classes[i].min, c->classes[i].max,
                  i + 1 == c->classes.size() ? "" : " (excl.)");
    std::printf("  no data  %s  %llu features\n", c->no_data_color.c_str(),
                static_cast<unsigned long long>(c->no_data));
  } else {
    std::printf("classes:");
    for (const NamedLineStyle& s : p.classes)
      std::printf(" %s", s.name.c_str());
    std::printf("\n");
  }
  std::printf("per zoom:\n  %4s %8s %10s %10s %12s\n", "zoom", "tiles", "polygons", "rings",
              "vertices");
  for (const auto& [z, c] : zooms)
    std::printf("  %4d %8llu %10llu %10llu %12llu\n", z, static_cast<unsigned long long>(c.tiles),
                static_cast<unsigned long long>(c.polygons),
                static_cast<unsigned long long>(c.rings),
                static_cast<unsigned long long>(c.vertices));
  return kExitOk;
}

int areas_validate(const std::string& path) {
  AreaPackage p = open_area_package(path);
  const tileformat::AreaMetadata& m = p.meta;
  ValidationReport r;
  tileformat::FeatureTableReader features(p.file());
  const int64_t max_id = features.max_id();
  const uint64_t classes =
      m.choropleth ? m.choropleth->classes.size() + 1 : std::max<size_t>(p.classes.size(), 1);
  Geos geos;
  uint64_t tiles = 0, polygons = 0, invalid = 0;
  p.file().for_each_tile([&](tileformat::TileId id, std::span<const uint8_t> blob) {
    const std::string where = path + " tile " + id.str();
    ++tiles;
    tileformat::AreaTile t;
    try {
      t = tileformat::decode_area_tile(blob);
    } catch (const tileformat::FormatError& e) {
      r.error(where + ": " + e.what());
      return;
    }
    if (id.z < m.common.min_zoom || id.z > m.common.max_zoom)
      r.warning(where + ": outside the metadata zoom range");
    if (int(t.extent) != m.extent || int(t.buffer) != m.buffer)
      r.error(where + ": extent/buffer " + std::to_string(t.extent) + "/" +
              std::to_string(t.buffer) + " differ from the metadata (tileformat §12.1)");
    for (uint64_t f : t.feature_ids)
      if (f < 1 || int64_t(f) > max_id)
        r.error(where + ": feature id " + std::to_string(f) + " not in the features table");
    for (const auto& [i, poly] : tile_polygons(t)) {
      ++polygons;
      if (t.polygons[i].class_id >= classes)
        r.error(where + ": polygon " + std::to_string(i) + " has class " +
                std::to_string(t.polygons[i].class_id) + ", the package has " +
                std::to_string(classes));
      if (!geos.is_valid({poly})) {
        ++invalid;
        r.warning(where + ": polygon " + std::to_string(i) + " of feature " +
                  std::to_string(t.feature_ids[t.polygons[i].feature]) +
                  " is not valid (GEOS): it still fills, its outline may cross itself");
      }
    }
  });
  std::printf("%s: %llu tiles, %llu polygons (%llu not valid): %llu errors, %llu warnings\n",
              path.c_str(), static_cast<unsigned long long>(tiles),
              static_cast<unsigned long long>(polygons), static_cast<unsigned long long>(invalid),
              static_cast<unsigned long long>(r.errors),
              static_cast<unsigned long long>(r.warnings));
  return r.exit_code();
}

int areas_extract(const ExtractRequest& rq) {
  AreaPackage p = open_area_package(rq.package);
  const tileformat::AreaMetadata& m = p.meta;
  if (rq.zoom < m.common.min_zoom || rq.zoom > m.common.max_zoom)
    throw UsageError("--zoom " + std::to_string(rq.zoom) + ": the package holds zooms " +
                     std::to_string(m.common.min_zoom) + ".." + std::to_string(m.common.max_zoom));
  VectorWriter out(rq.output,
                   rq.force ? tileformat::IfExists::kOverwrite : tileformat::IfExists::kFail,
                   m.common.tiling.crs);
  tileformat::FeatureTableReader features(p.file());
  const tileformat::Tiling& tiling = m.common.tiling;
  Geos geos;
  p.file().for_each_tile(
      [&](tileformat::TileId id, std::span<const uint8_t> blob) {
        const tileformat::AreaTile t = tileformat::decode_area_tile(blob);
        const tileformat::Bounds b = tiling.tile_bounds(id);
        const double unit = b.width() / t.extent, e = t.extent;
        for (const auto& [i, poly] : tile_polygons(t)) {
          const tileformat::AreaPolygon& a = t.polygons[i];
          VectorAttributes attrs;
          attrs.feature_id = static_cast<int64_t>(t.feature_ids[a.feature]);
          attrs.tile = id.str();
          if (m.choropleth)
            attrs.class_name = a.class_id == 0 ? "no data" : std::to_string(a.class_id);
          else if (a.class_id < p.classes.size())
            attrs.class_name = p.classes[a.class_id].name;
          if (auto f = features.get(attrs.feature_id)) {
            attrs.layer = f->layer;
            attrs.properties = f->properties;
          }
          for (const PlanePolygon& piece : geos.clip({poly}, 0, 0, e, e)) {
            std::vector<std::vector<XY>> rings;
            for (const PlaneRing& ring : piece) {
              rings.emplace_back();
              for (const PlanePoint& q : ring)
                rings.back().push_back({b.min_x + q.x * unit, b.max_y - q.y * unit});
            }
            out.add_polygon(rings, attrs);
          }
        }
      },
      rq.zoom);
  out.commit();
  if (!rq.quiet)
    std::fprintf(stderr, "globe-vectorize: wrote %s: %llu polygons of zoom %d\n", rq.output.c_str(),
                 static_cast<unsigned long long>(out.polygons()), rq.zoom);
  return kExitOk;
}

}  // namespace

// This kind's row of the tool's table (inspect/inspect_commands.cpp).
extern const KindInspection kAreasInspection{tileformat::PackageKind::kAreas, areas_info,
                                             areas_validate, areas_extract};

}  // namespace globe
