// Line packages to Mapbox Vector Tiles (see mvt_export.hpp).
#include "export/mvt_export.hpp"

#include <chrono>
#include <filesystem>
#include <fstream>
#include <optional>

#include "runtime/errors.hpp"
#include "runtime/line_package.hpp"
#include "tileformat/label_table.hpp"
#include "tileformat/pmtiles.hpp"
#include "web/glyphs.hpp"
#include "web/gzip.hpp"
#include "web/line_mvt.hpp"
#include "web/mvt_encoder.hpp"
#include "web/tile_output.hpp"

namespace globe {

std::string mvt_source_url(const std::string& output) {
  const std::string name = std::filesystem::path(output).filename().string();
  switch (output_kind(output)) {
    case OutputKind::kPmtiles:
      return "pmtiles://" + name;
    case OutputKind::kDirectory:
      return name + "/metadata.json";
    default:
      return name;
  }
}

std::string glyphs_url(const std::string& style_json, const std::string& glyphs_dir) {
  namespace fs = std::filesystem;
  const fs::path from = fs::absolute(fs::path(style_json)).parent_path().lexically_normal();
  const fs::path to = fs::absolute(fs::path(glyphs_dir)).lexically_normal();
  std::string rel = to.lexically_relative(from).generic_string();
  while (!rel.empty() && rel.back() == '/')
    rel.pop_back();
  if (rel.empty() || rel == ".") return "{fontstack}/{range}.pbf";
  return rel + "/{fontstack}/{range}.pbf";
}

void write_style_json(const std::string& path, const std::string& style) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp);
    out << style << "\n";
    if (!out) throw OutputError(tmp + ": cannot write (disk full?)");
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) throw OutputError(path + ": cannot write (" + ec.message() + ")");
}

MvtExportSummary write_vector_tiles(
    const MvtExportSettings& s, Progress& progress, tileformat::PackageReader& reader,
    const tileformat::CommonMetadata& common,
    const std::function<std::vector<uint8_t>(tileformat::TileId, std::span<const uint8_t>)>& encode,
    const std::function<void(ExportInfo&)>& describe,
    const std::function<std::string(const std::string&, const web::StyleGlyphs&)>& style) {
  const auto start = std::chrono::steady_clock::now();
  if (common.tiling.scheme != tileformat::Scheme::kWebMercator)
    throw UsageError(s.input +
                     ": web maps read web mercator vector tiles and this package is in the " +
                     std::string(tileformat::scheme_name(common.tiling.scheme)) +
                     " tiling; build it with --tiling webmercator");
  // The glyphs of the style's labels (beside the style unless told where):
  // their fonts are found before any output is made.
  const bool labelled = tileformat::has_labels(reader);
  std::string glyphs_dir = s.glyphs_dir;
  if (glyphs_dir.empty() && labelled && !s.style_json.empty())
    glyphs_dir =
        (std::filesystem::path(s.style_json).parent_path() / "fonts").lexically_normal().string();
  std::optional<web::GlyphSet> fonts;
  if (!glyphs_dir.empty()) fonts.emplace();
  const std::vector<tileformat::TileId> items =
      tiles_in_output_order(reader, common.min_zoom, common.max_zoom);
  std::unique_ptr<TileOutput> out = TileOutput::open(s.output, s.force, "pbf", false);
  progress.begin("encode vector tiles", items.size());
  for (const tileformat::TileId& it : items) {
    const auto blob = reader.tile(it);
    progress.advance();
    if (!blob) continue;
    const std::vector<uint8_t> tile = encode(it, *blob);
    if (!tile.empty()) out->put(it.z, it.x, it.y, web::gzip(tile));
  }
  progress.end();

  ExportInfo info;
  info.name = std::filesystem::path(s.output).stem().string();
  info.format = "pbf";
  info.extension = "pbf";
  info.type = "overlay";
  info.tile_type = tileformat::pmtiles::TileType::kMvt;
  info.tile_compression = tileformat::pmtiles::Compression::kGzip;
  info.min_zoom = common.min_zoom, info.max_zoom = common.max_zoom;
  const tileformat::Bounds& b = common.lonlat;
  info.west = b.min_x, info.south = b.min_y, info.east = b.max_x, info.north = b.max_y;
  describe(info);
  MvtExportSummary sum;
  sum.tiles = out->tiles();
  sum.bytes = out->finish(info);
  if (labelled) sum.labels = uint64_t(tileformat::LabelTableReader(reader).count());
  web::StyleGlyphs glyphs;
  if (fonts) {
    sum.glyphs_dir = glyphs_dir;
    sum.glyph_files = fonts->write(glyphs_dir);
    if (labelled && !s.style_json.empty())
      glyphs = {glyphs_url(s.style_json, glyphs_dir), fonts->fontstack()};
  }
  if (!s.style_json.empty())
    write_style_json(s.style_json, style(mvt_source_url(s.output), glyphs));
  sum.min_zoom = common.min_zoom, sum.max_zoom = common.max_zoom;
  sum.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return sum;
}

MvtExportSummary export_mvt(const MvtExportSettings& s, Progress& progress) {
  LinePackage pkg = open_line_package(s.input);
  web::LineMvtEncoder encoder(pkg);
  MvtExportSummary sum = write_vector_tiles(
      s, progress, pkg.file(), pkg.meta.common,
      [&](tileformat::TileId id, std::span<const uint8_t> blob) {
        return encoder.encode(id, blob);
      },
      [&](ExportInfo& info) {
        info.description = "Lines of " + s.input + " as Mapbox Vector Tiles 2.1 (gzip)";
        info.extra_json = "\"vector_layers\":" + web::vector_layers_json(encoder.fields());
      },
      [&](const std::string& url, const web::StyleGlyphs& glyphs) {
        return web::line_style_json(pkg, encoder.classes_in(), url, glyphs);
      });
  sum.features = encoder.features();
  sum.zero_length = encoder.zero_length();
  return sum;
}

}  // namespace globe
