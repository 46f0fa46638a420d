// The cluster grid of line and point tiles (docs/tileformat.md §7.3,
// §11.3), private to lib: per cell of a grid x grid the number of its
// entries, then per cell the items it lists (segments, places) ascending,
// the first as it is and each next as its gap to the one before minus one.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "tileformat/byte_io.hpp"

namespace tileformat {

// offsets: cells + 1 running totals into items.
void write_cell_lists(ByteWriter& out, const std::vector<uint32_t>& offsets,
                      const std::vector<uint32_t>& items);

// Reads `cells` cells of `entries` entries in all, each an index below
// `item_count` (`item_name` in errors); fails (r.fail) on counts that do not
// sum to `entries` and on lists out of range or not ascending.
void read_cell_lists(ByteReader& r, size_t cells, uint32_t entries, uint32_t item_count,
                     const char* item_name, std::vector<uint32_t>& offsets,
                     std::vector<uint32_t>& items);

}  // namespace tileformat
