// `globe-vectorize export LINES --format mvt` (docs/web.md "Vector tiles"): a
// line-cluster package (lines, bundles) as Mapbox Vector Tiles 2.1, one MVT
// layer per layer of the features table ("roads", "bundles", "unrouted"),
// each run of a tile a LINESTRING with the feature's id, its class ("class")
// and its attributes from the features table; tile coordinates as stored
// (extent 4096, the margin as the MVT buffer); tiles gzipped. Optionally a
// MapLibre style (version 8) that draws the classes with the package's
// colours, widths, dashes, casings and opacities; for a package with labels
// the names as "name" and the style's symbol layers, whose glyph PBFs are
// written beside the style (docs/web.md "Labels").
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "kit/progress.hpp"
#include "tileformat/metadata.hpp"
#include "tileformat/package.hpp"
#include "web/mvt_labels.hpp"
#include "web/tile_output.hpp"

namespace globe {

struct MvtExportSettings {
  std::string input, output;
  std::string style_json;  // "" = none
  // Where the glyph PBFs go: "" = DIR/fonts beside the style when the
  // package has labels and a style is written, else none.
  std::string glyphs_dir;
  bool force = false;
};

struct MvtExportSummary {
  uint64_t tiles = 0, bytes = 0, features = 0, zero_length = 0;
  uint64_t labels = 0, glyph_files = 0;
  std::string glyphs_dir;  // where the glyph PBFs went ("" = none written)
  int min_zoom = 0, max_zoom = 0;
  double seconds = 0;
};

MvtExportSummary export_mvt(const MvtExportSettings& s, Progress& progress);

// What both vector exports do around their tile encoder: refuse a tiling
// other than web mercator, encode every tile of the package's zooms in
// output order (`encode`: MVT bytes, empty for none), gzip each into the
// output, let `describe` fill the description and vector_layers, finish the
// output, write the glyph PBFs where the settings say (glyphs.hpp) and
// `style(source_url, glyphs)` to --style-json if asked (`glyphs` empty
// unless the package has labels).
MvtExportSummary write_vector_tiles(
    const MvtExportSettings& s, Progress& progress, tileformat::PackageReader& reader,
    const tileformat::CommonMetadata& common,
    const std::function<std::vector<uint8_t>(tileformat::TileId, std::span<const uint8_t>)>& encode,
    const std::function<void(ExportInfo&)>& describe,
    const std::function<std::string(const std::string&, const web::StyleGlyphs&)>& style);

// The URL a generated style gives its source, relative to the style's folder:
// pmtiles://NAME.pmtiles, NAME.mbtiles, or DIR/metadata.json.
std::string mvt_source_url(const std::string& output);
// The "glyphs" URL of a style at `style_json` for PBFs written into
// `glyphs_dir`: relative to the style's folder, "DIR/{fontstack}/{range}.pbf".
std::string glyphs_url(const std::string& style_json, const std::string& glyphs_dir);
// Writes a style file whole (PATH.tmp renamed); throws OutputError.
void write_style_json(const std::string& path, const std::string& style);

}  // namespace globe
