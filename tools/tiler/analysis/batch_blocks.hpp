// The terrain blocks one batch of analysis work reads: blobs fetched by the
// caller's thread (the only one touching SQLite), each decoded once, by the
// first worker that needs it, and shared read-only by the others.
#pragma once

#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "runtime/errors.hpp"
#include "tileformat/error.hpp"
#include "tileformat/mblock.hpp"
#include "tileformat/tile_id.hpp"

namespace globe {

class BatchBlocks {
 public:
  void add(tileformat::TileId id, std::optional<std::vector<uint8_t>> blob) {
    if (slots_.count(id)) return;
    auto slot = std::make_unique<Slot>();
    slot->blob = std::move(blob);
    slots_.emplace(id, std::move(slot));
  }
  bool has(tileformat::TileId id) const { return slots_.count(id) != 0; }
  // Null where there is no tile. Throws InputError for a corrupt block,
  // naming `path` and the tile.
  const tileformat::MBlock* get(tileformat::TileId id, const std::string& path) const {
    const auto it = slots_.find(id);
    if (it == slots_.end() || !it->second->blob) return nullptr;
    Slot& s = *it->second;
    std::call_once(s.once, [&] {
      try {
        s.block = tileformat::decode_mblock(*s.blob);
        std::vector<uint8_t>().swap(*s.blob);  // decoded: the blob's memory goes
      } catch (const tileformat::FormatError& e) {
        throw InputError(path + ": tile " + id.str() + ": " + e.what() +
                         "; rebuild the terrain package (globe-tiler validate lists bad tiles)");
      }
    });
    return &s.block;
  }

 private:
  struct Slot {
    std::optional<std::vector<uint8_t>> blob;
    std::once_flag once;
    tileformat::MBlock block;
  };
  std::map<tileformat::TileId, std::unique_ptr<Slot>> slots_;
};

}  // namespace globe
