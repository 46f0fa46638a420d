// Mapbox Vector Tile 2.1 (mapbox/vector-tile-spec 2.1, written from the spec):
// the protobuf Tile of layers of features with tags and geometry commands, as
// MapLibre GL, GDAL's MVT driver and tippecanoe read them. Coordinates are
// tile-local integers (x east, y south, 0..extent; beyond: the buffer).
#pragma once

#include <cstdint>
#include <map>
#include <span>
#include <string>
#include <vector>

#include "tileformat/json.hpp"

namespace globe::web {

struct MvtPoint {
  int32_t x = 0, y = 0;
  bool operator==(const MvtPoint&) const = default;
};

// A tag value (spec 4.1 "Value"): text, number or boolean.
struct MvtValue {
  enum class Kind { kString, kDouble, kInt, kBool } kind = Kind::kString;
  std::string text;
  double number = 0;
  int64_t integer = 0;
  bool flag = false;
  bool operator<(const MvtValue& o) const;
  // A JSON attribute as a tag: integral numbers as int, other numbers as
  // double, booleans, strings; arrays and objects as their JSON text.
  static MvtValue from_json(const tileformat::JsonValue& v);
};

class MvtLayer {
 public:
  MvtLayer(std::string name, uint32_t extent) : name_(std::move(name)), extent_(extent) {}
  // A LINESTRING (consecutive equal vertices merged). A line of one distinct
  // position, which MVT cannot hold as a line, becomes a POINT there with the
  // tag "zero_length": true (docs/web.md); returns false then.
  bool add_line(uint64_t id, std::span<const MvtPoint> line,
                const std::vector<std::pair<std::string, MvtValue>>& tags);
  void add_point(uint64_t id, MvtPoint at,
                 const std::vector<std::pair<std::string, MvtValue>>& tags);
  // A POLYGON (one exterior ring) or MULTIPOLYGON: rings open (the first
  // vertex not repeated), exterior rings with positive area in tile
  // coordinates (y down), each followed by its holes (negative area), as
  // spec 4.3.4.4 wants; rings of fewer than 3 vertices are left out.
  void add_polygon(uint64_t id, const std::vector<std::vector<MvtPoint>>& rings,
                   const std::vector<std::pair<std::string, MvtValue>>& tags);
  bool empty() const { return features_.empty(); }
  const std::string& name() const { return name_; }
  // The Layer message (spec 4.1), without its field key.
  std::string encode() const;

 private:
  uint32_t tag_key(const std::string& key);
  uint32_t tag_value(const MvtValue& v);
  void add(uint64_t id, int type, std::vector<uint32_t> geometry,
           const std::vector<std::pair<std::string, MvtValue>>& tags);

  std::string name_;
  uint32_t extent_;
  std::vector<std::string> features_;  // encoded Feature messages
  std::vector<std::string> keys_;
  std::vector<MvtValue> values_;
  std::map<std::string, uint32_t> key_index_;
  std::map<MvtValue, uint32_t> value_index_;
};

// The Tile message of `layers` (empty layers left out).
std::vector<uint8_t> encode_mvt(const std::vector<MvtLayer>& layers);

// TileJSON's "vector_layers" array: per layer its id and fields (name -> type,
// "String", "Number" or "Boolean").
std::string vector_layers_json(
    const std::map<std::string, std::map<std::string, std::string>>& layers);

}  // namespace globe::web
