// The terrain builder's staged data (terrain_builder.hpp, raster_stages.hpp),
// each coded once here in the project's one byte codec
// (tileformat/byte_io.hpp) or the MBlock height coding:
//   kRaw, kQuarter   encode_scratch: a height grid, zstd level 1, no header
//   kEdges           pack_edges: a block's first row and column
//   kNodeErrors      pack_errors: a block's node errors, u32 each
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "tileformat/shard_table.hpp"

namespace globe {

// Parts of a terrain shard's table (tileformat/shard_table.hpp), coded as
// the stages of the same name: node errors near the shard's border and at
// the split zoom, quarters at the split zoom.
enum TerrainShardPart : tileformat::ShardPartTag { kShardNodeErrors = 1, kShardQuarter = 2 };

// A block of height quanta and validity flags, size x size, row-major.
struct Block {
  std::vector<int32_t> q;
  std::vector<uint8_t> valid;  // always size*size here
};

std::vector<uint8_t> encode_scratch(const Block& b, int size);
Block decode_scratch(std::span<const uint8_t> bytes);
// Every other sample of a final block of `steps` + 1 samples a side: what its
// parent takes (pass 1 of the next coarser zoom), a quarter of the samples to
// store and read back. Coded like encode_scratch.
std::vector<uint8_t> encode_quarter(const Block& b, int steps);

// First row and first column of a block (x or y = 0 .. steps), what its
// west/north neighbours take from it: per sample, the height quantum (i32)
// then validity (u8). Samples the block does not own are invalid in it.
std::vector<uint8_t> pack_edges(const Block& b, int size);
// Unpacked edges: sample k < size is row 0 at x = k, else column 0 at y = k - size.
Block unpack_edges(std::span<const uint8_t> bytes, int size);

std::vector<uint8_t> pack_errors(const std::vector<uint32_t>& errors);
std::vector<uint32_t> unpack_errors(std::span<const uint8_t> bytes);

}  // namespace globe
