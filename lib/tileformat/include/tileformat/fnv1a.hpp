// FNV-1a, 64 bits: the content hash that finds identical tiles (packages,
// PMTiles archives). Not cryptographic: equal hashes are compared byte by byte.
#pragma once

#include <cstdint>
#include <span>

namespace tileformat {

inline uint64_t fnv1a(std::span<const uint8_t> bytes) {
  uint64_t h = 1469598103934665603ull;
  for (uint8_t b : bytes)
    h = (h ^ b) * 1099511628211ull;
  return h;
}

}  // namespace tileformat
