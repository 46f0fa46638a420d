// Area packages to Mapbox Vector Tiles (see area_mvt_export.hpp).
#include "export/area_mvt_export.hpp"

#include "runtime/area_package.hpp"
#include "web/area_mvt.hpp"
#include "web/mvt_encoder.hpp"
#include "web/tile_output.hpp"

namespace globe {

MvtExportSummary export_area_mvt(const MvtExportSettings& s, Progress& progress) {
  AreaPackage pkg = open_area_package(s.input);
  web::AreaMvtEncoder encoder(pkg);
  MvtExportSummary sum = write_vector_tiles(
      s, progress, pkg.file(), pkg.meta.common,
      [&](tileformat::TileId id, std::span<const uint8_t> blob) {
        return encoder.encode(id, blob);
      },
      [&](ExportInfo& info) {
        info.description = "Areas of " + s.input + " as Mapbox Vector Tiles 2.1 (gzip)";
        info.extra_json = "\"vector_layers\":" + web::vector_layers_json(encoder.fields());
      },
      [&](const std::string& url, const web::StyleGlyphs& glyphs) {
        return web::area_style_json(pkg, encoder.classes_in(), url, glyphs);
      });
  sum.features = encoder.features();
  return sum;
}

}  // namespace globe
