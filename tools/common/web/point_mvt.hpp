// Point tiles as Mapbox Vector Tiles (docs/web.md "Vector tiles"), one tile at
// a time, for the export and the server: one MVT layer "points", each place a
// POINT with its id (an aggregate's: the smallest of its places), "count"
// (the source places it stands for) and one number per field. Also a MapLibre
// style drawing the places as circles sized by count.
#pragma once

#include <cstdint>
#include <map>
#include <span>
#include <string>
#include <vector>

#include "runtime/point_package.hpp"
#include "tileformat/tile_id.hpp"

namespace globe::web {

// The MVT bytes (not gzipped; empty if the tile holds no place) of a tile's
// blob. Throws InputError naming the package and tile for a blob that does
// not decode.
std::vector<uint8_t> point_tile_mvt(const PointPackage& package, tileformat::TileId id,
                                    std::span<const uint8_t> blob, uint64_t* places = nullptr);

// TileJSON's fields of layer "points": count and every field, all numbers.
std::map<std::string, std::map<std::string, std::string>> point_mvt_fields(
    const PointPackage& package);

std::string point_style_json(const PointPackage& package, const std::string& source_url);

}  // namespace globe::web
