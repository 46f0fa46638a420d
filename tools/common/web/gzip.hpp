// The one wrapper of zlib: gzip (RFC 1952) of bytes in memory, for vector
// tiles (MVT is served and stored gzipped by convention: Content-Encoding
// gzip, PMTiles tile compression 2).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace globe::web {

// Throws std::runtime_error if zlib fails. Deterministic: no time or name in
// the header.
std::vector<uint8_t> gzip(std::span<const uint8_t> bytes, int level = 6);

}  // namespace globe::web
