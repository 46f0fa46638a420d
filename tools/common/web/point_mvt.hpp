// Point tiles as Mapbox Vector Tiles (docs/web.md "Vector tiles"), one tile at
// a time, for the export and the server: one MVT layer "points", each place a
// POINT with its id (an aggregate's: the smallest of its places), "count"
// (the source places it stands for), one number per field and, for a place
// of its own (count 1) with a label, "name" (mvt_labels.hpp). Also a
// MapLibre style drawing the places as circles sized by count, and the names
// beside them.
#pragma once

#include <cstdint>
#include <map>
#include <span>
#include <string>
#include <vector>

#include "runtime/point_package.hpp"
#include "tileformat/tile_id.hpp"
#include "web/mvt_labels.hpp"

namespace globe::web {

// The MVT bytes (not gzipped; empty if the tile holds no place) of a tile's
// blob; `labels` (may be null): the package's, for the places' names (an
// aggregate of several places is not named after one of them). Throws
// InputError naming the package and tile for a blob that does not decode.
std::vector<uint8_t> point_tile_mvt(const PointPackage& package, tileformat::TileId id,
                                    std::span<const uint8_t> blob, uint64_t* places = nullptr,
                                    const MvtLabels* labels = nullptr);

// TileJSON's fields of layer "points": count and every field, all numbers;
// "name" (text) when `labels` holds any.
std::map<std::string, std::map<std::string, std::string>> point_mvt_fields(
    const PointPackage& package, const MvtLabels* labels = nullptr);

// Circles sized by count; unless `glyphs` is empty, a symbol layer
// "points:labels" with each named place's name beside its circle.
std::string point_style_json(const PointPackage& package, const std::string& source_url,
                             const StyleGlyphs& glyphs = {});

}  // namespace globe::web
