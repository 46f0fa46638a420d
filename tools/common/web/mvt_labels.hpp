// A vector package's labels as its Mapbox Vector Tiles and MapLibre styles
// carry them (docs/web.md "Labels"), for the line, point and area encoders
// (line_mvt, point_mvt, area_mvt) and their styles: each labelled feature's
// text for its `name` tag, and the area labels' anchors, each in the one
// tile of a zoom that holds it (a point repeated in the tiles around an edge
// would be drawn once per tile: MapLibre GL JS issue 5042), ranked by
// priority. Read once from the labels table (tileformat/label_table.hpp).
// glyphs.hpp writes and serves the glyphs the styles' symbol layers need.
#pragma once

#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

#include "tileformat/package.hpp"
#include "tileformat/tile_id.hpp"
#include "web/feature_tags.hpp"
#include "web/mvt_encoder.hpp"

namespace globe::web {

class MvtLabels {
 public:
  // Reads the package's labels table (none: empty). Throws InputError naming
  // the package for a table that does not decode. Keeps every text in
  // memory (about 60 bytes a label). Immutable afterwards: const members
  // are safe from several threads.
  explicit MvtLabels(tileformat::PackageReader& reader);

  bool empty() const { return text_.empty(); }
  size_t size() const { return text_.size(); }
  // The label text of feature `id` (features.id), nullptr when it has none.
  const std::string* text(uint64_t feature) const;

  // An area label's anchor in a tile: its feature, its rank (1 for the
  // highest priority, then down; ties by the labels' order) and its
  // position in tile units (y down).
  struct Anchor {
    uint64_t feature = 0;
    int64_t rank = 0;
    MvtPoint at;
  };
  // The anchors of the area labels (placement area) in web mercator tile
  // `id` (XYZ rows), each anchor in exactly one tile of a zoom (its
  // position's floor; latitudes past 85.0511 degrees in the edge rows), in
  // rank order.
  std::vector<Anchor> anchors_in(tileformat::TileId id, uint32_t extent) const;

 private:
  struct Entry {
    uint64_t key = 0;  // Morton code of the position on a 2^32 grid
    uint64_t feature = 0;
    int64_t rank = 0;
    double x = 0, y = 0;  // web mercator, 0..1 from the west and the north
  };
  std::unordered_map<uint64_t, std::string> text_;
  std::vector<Entry> anchors_;  // by key, then rank
};

// Sets `tags`' "name" to `text`: in place of an attribute of that name, else last.
void set_name_tag(MvtTags& tags, const std::string& text);

// What a generated MapLibre style needs to draw labels: its "glyphs" URL
// (with {fontstack} and {range}) and the fontstack its symbol layers name.
// Empty: a style without labels.
struct StyleGlyphs {
  std::string url, fontstack;
  bool empty() const { return url.empty() || fontstack.empty(); }
};

// `,"glyphs":"URL"` for a style object, or "" when `glyphs` is empty.
std::string style_glyphs_member(const StyleGlyphs& glyphs);

// A symbol layer drawing each feature's "name" of `source_layer`: the
// fontstack at 12 px, #222 with a white halo of 1.5 px; `layout` adds
// members to the layout object (placement, anchors, sort key), starting with
// a comma.
std::string label_layer_json(const std::string& id, const std::string& source,
                             const std::string& source_layer, const StyleGlyphs& glyphs,
                             const std::string& layout);

}  // namespace globe::web
