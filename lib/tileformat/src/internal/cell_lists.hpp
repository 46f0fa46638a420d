// The lists line and point tiles share, private to lib: their ids (features
// §7.2, places §11.2) and their cluster grid (§7.3, §11.3). Both are
// ascending lists coded the same way: the first as it is, each next as its
// gap to the one before minus one. The grid is per cell of a grid x grid
// the number of its entries, then per cell the items it lists (segments,
// places).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "tileformat/byte_io.hpp"

namespace tileformat {

// Strictly increasing ids; throws FormatError citing `section` (naming them
// `what`: "line tile: feature") if they are not.
void write_increasing_ids(ByteWriter& out, std::span<const uint64_t> ids, const char* section,
                          const char* what);
// Reads `count` of them; fails (r.fail) when one overflows 64 bits.
std::vector<uint64_t> read_increasing_ids(ByteReader& r, uint32_t count, const char* what);

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
