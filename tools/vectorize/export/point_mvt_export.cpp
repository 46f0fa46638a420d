// Point packages to Mapbox Vector Tiles (see point_mvt_export.hpp).
#include "export/point_mvt_export.hpp"

#include "runtime/point_package.hpp"
#include "web/mvt_encoder.hpp"
#include "web/point_mvt.hpp"
#include "web/tile_output.hpp"

namespace globe {

MvtExportSummary export_point_mvt(const MvtExportSettings& s, Progress& progress) {
  PointPackage pkg = open_point_package(s.input);
  const web::MvtLabels labels(pkg.file());
  uint64_t places = 0;
  MvtExportSummary sum = write_vector_tiles(
      s, progress, pkg.file(), pkg.meta.common,
      [&](tileformat::TileId id, std::span<const uint8_t> blob) {
        return web::point_tile_mvt(pkg, id, blob, &places, &labels);
      },
      [&](ExportInfo& info) {
        info.description =
            "Places of " + s.input + " as Mapbox Vector Tiles 2.1 (gzip); values are " +
            (pkg.meta.aggregate == tileformat::PointAggregate::kMean ? "means" : "sums") +
            " over the places each stands for";
        info.extra_json =
            "\"vector_layers\":" + web::vector_layers_json(web::point_mvt_fields(pkg, &labels));
      },
      [&](const std::string& url, const web::StyleGlyphs& glyphs) {
        return web::point_style_json(pkg, url, glyphs);
      });
  sum.features = places;
  return sum;
}

}  // namespace globe
