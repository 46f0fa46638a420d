// The 12-byte header every tile blob starts with (docs/tileformat.md §4):
// magic "GLOB", format version, blob kind and the body length, so a reader can
// reject foreign data, newer versions and truncated or padded blobs up front.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace tileformat {

enum class BlobKind : uint16_t {
  kMBlock = 1,
  kImage = 2,
  kLineClusters = 3,
  kAnalysis = 4,
  kPoints = 5,
  kAreas = 6
};

// Every blob kind and its name in messages (adding a kind: its enumerator
// and its row).
struct BlobKindName {
  BlobKind kind;
  const char* name;
};
inline constexpr BlobKindName kBlobKinds[] = {{BlobKind::kMBlock, "mblock"},
                                              {BlobKind::kImage, "image"},
                                              {BlobKind::kLineClusters, "lineclusters"},
                                              {BlobKind::kAnalysis, "analysis block"},
                                              {BlobKind::kPoints, "points"},
                                              {BlobKind::kAreas, "areas"}};

inline constexpr uint16_t kFormatVersion = 1;
inline constexpr size_t kBlobHeaderSize = 12;

std::string blob_kind_name(BlobKind kind);

// Returns header + body.
std::vector<uint8_t> wrap_blob(BlobKind kind, std::span<const uint8_t> body);

// Checks magic, version, kind and exact length; returns the body.
// Throws FormatError (§4) on any mismatch.
std::span<const uint8_t> read_blob_header(std::span<const uint8_t> blob, BlobKind expected);

// Peeks the kind of a blob without decoding it; throws FormatError if the
// header itself is invalid.
BlobKind peek_blob_kind(std::span<const uint8_t> blob);

}  // namespace tileformat
