// Line, point and area tiles drawn as transparent PNG images, as the
// generated MapLibre styles draw them (line_mvt.hpp, point_mvt.hpp,
// area_mvt.hpp), for clients that
// drape images but read no vector tiles: CesiumJS's imagery layers in
// globe-serve's composed preview (docs/serve.md "Preview"). Lines: classes
// in id order, every casing under every fill, round caps and joins, widths in
// pixels (or metres at the tile's centre latitude), opacity; dashes and
// patterns are drawn solid. Points: circles whose radius follows the square
// root of the count (3 px at 1 to 30 px at 100), #d7301f at 0.8 with a white
// rim. Anti-aliased by the distance of each pixel's centre, 1 px wide ramps.
// Areas: each polygon filled by the nonzero winding rule (scanlines, 4 x 4
// samples a pixel) in its class's colour (a choropleth's class colour, or
// the no-data colour) at the style's opacity, the fills of all classes added
// so that two polygons sharing a border leave no seam; then the outlines
// (#444444, 0.5 px, 0.8) over them.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <vector>

#include "runtime/area_package.hpp"
#include "runtime/line_package.hpp"
#include "runtime/point_package.hpp"
#include "tileformat/tile_id.hpp"

namespace globe::web {

// The PNG (RGBA, `size` pixels square) of line tile `id` from its blob; an
// empty vector if nothing is drawn in it. Throws InputError naming the
// package and tile for a blob that does not decode.
std::vector<uint8_t> line_tile_png(const LinePackage& package, tileformat::TileId id,
                                   std::span<const uint8_t> blob, int size = 256);

// The same for point tile `id`; `blob_of` gives the blob of a tile (nullopt:
// none), asked for `id` and its eight neighbours, whose circles reach over
// the edge.
std::vector<uint8_t> point_tile_png(
    const PointPackage& package, tileformat::TileId id,
    const std::function<std::optional<std::vector<uint8_t>>(tileformat::TileId)>& blob_of,
    int size = 256);

// The PNG of area tile `id` from its blob (as line_tile_png). A polygon
// reaches only `buffer` units past its tile, which the drawing never needs.
std::vector<uint8_t> area_tile_png(const AreaPackage& package, tileformat::TileId id,
                                   std::span<const uint8_t> blob, int size = 256);

}  // namespace globe::web
