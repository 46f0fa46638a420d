// The one wrapper around libzstd: compress, and decompress into a buffer of a
// size the caller already knows (from the blob), rejecting any other size.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace tileformat::detail {

std::vector<uint8_t> zstd_compress(std::span<const uint8_t> in, int level);

// Throws FormatError(section) unless `in` is one complete zstd frame that
// decompresses to exactly `expected_size` bytes.
std::vector<uint8_t> zstd_decompress(std::span<const uint8_t> in, size_t expected_size,
                                     const std::string& what, const std::string& section);

}  // namespace tileformat::detail
