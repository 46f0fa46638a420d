// Native tiles for globe-view (see native_tiles.hpp).
#include "serve/native_tiles.hpp"

#include "tileformat/json.hpp"

namespace globe::serve {

NativeTiles::NativeTiles(const std::string& path) : reader_(path) {
  for (const tileformat::ZoomSummary& z : reader_.zoom_summaries()) {
    if (!z.tiles) continue;
    zooms_ += std::string(zooms_.empty() ? "" : ",") + "[" + std::to_string(z.zoom) + "," +
              std::to_string(z.min_x) + "," + std::to_string(z.max_x) + "," +
              std::to_string(z.min_y) + "," + std::to_string(z.max_y) + "]";
  }
}

std::optional<std::vector<uint8_t>> NativeTiles::tile(tileformat::TileId id) {
  std::lock_guard lock(mutex_);
  return reader_.tile(id);
}

std::string NativeTiles::tilejson_member(const std::string& base) const {
  std::string out = "\"globe\":{\"tiles\":[\"" + tileformat::json_escape(base) +
                    "/{z}/{x}/{y}.globe\"],\"zooms\":[" + zooms_ + "],\"metadata\":{";
  bool first = true;
  for (const auto& [key, value] : reader_.metadata()) {
    if (!first) out += ",";
    first = false;
    out += "\"" + tileformat::json_escape(key) + "\":\"" + tileformat::json_escape(value) + "\"";
  }
  return out + "}}";
}

std::string with_member(std::string tilejson, const std::string& member) {
  const size_t close = tilejson.find_last_of('}');
  if (close == std::string::npos) return tilejson;
  const size_t open = tilejson.find_first_of('{');
  const bool empty = tilejson.find_first_not_of(" \t\r\n", open + 1) == close;
  tilejson.insert(close, (empty ? "" : ",") + member);
  return tilejson;
}

}  // namespace globe::serve
