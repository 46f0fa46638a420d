// The one wrapper around libzstd: compress, and decompress into a buffer of a
// size the caller already knows (from the blob), rejecting any other size.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace tileformat {

// How zstd searches for matches: its own choice for the level; its "lazy"
// strategy with 4-byte matches, which on MBlock byte planes at level 9 gives
// the same size (within 0.01 %) in 25 % less time than the level's own
// "lazy2" (measured on etopo20 and a 5' global grid); or the level's own
// strategy taking only matches of 6 bytes or more, which suits residuals
// packed four to a byte (shorter matches there are mostly chance).
enum class ZstdSearch { kLevelDefault, kLazy, kLongMatches };

std::vector<uint8_t> zstd_compress(std::span<const uint8_t> in, int level,
                                   ZstdSearch search = ZstdSearch::kLevelDefault);

// Throws FormatError(section) unless `in` is one complete zstd frame that
// decompresses to exactly `expected_size` bytes.
std::vector<uint8_t> zstd_decompress(std::span<const uint8_t> in, size_t expected_size,
                                     const std::string& what, const std::string& section);

}  // namespace tileformat
