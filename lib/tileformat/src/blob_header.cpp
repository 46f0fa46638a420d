// Blob header (docs/tileformat.md §4).
#include "tileformat/blob_header.hpp"

#include "tileformat/byte_io.hpp"

namespace tileformat {
namespace {
constexpr uint8_t kMagic[4] = {'G', 'L', 'O', 'B'};

struct Header {
  uint16_t version;
  uint16_t kind;
  uint32_t body_size;
};

bool known_kind(uint16_t kind) {
  for (const BlobKindName& k : kBlobKinds)
    if (static_cast<uint16_t>(k.kind) == kind) return true;
  return false;
}

Header parse(std::span<const uint8_t> blob, ByteReader& r) {
  auto magic = r.bytes(4);
  for (int i = 0; i < 4; ++i)
    if (magic[i] != kMagic[i]) r.fail("bad magic (not a GlobeEngine tile blob)");
  Header h{r.u16(), r.u16(), r.u32()};
  if (h.version == 0 || h.version > kFormatVersion)
    r.fail("format version " + std::to_string(h.version) +
           " is not supported (this reader knows 1.." + std::to_string(kFormatVersion) +
           "; upgrade the reader)");
  if (!known_kind(h.kind)) r.fail("unknown blob kind " + std::to_string(h.kind));
  if (blob.size() - kBlobHeaderSize < h.body_size)
    r.fail("truncated: header declares " + std::to_string(h.body_size) + " body bytes, blob has " +
           std::to_string(blob.size() - kBlobHeaderSize));
  if (blob.size() - kBlobHeaderSize > h.body_size)
    r.fail(std::to_string(blob.size() - kBlobHeaderSize - h.body_size) + " trailing bytes");
  return h;
}
}  // namespace

std::string blob_kind_name(BlobKind kind) {
  for (const BlobKindName& k : kBlobKinds)
    if (k.kind == kind) return k.name;
  return "unknown(" + std::to_string(static_cast<int>(kind)) + ")";
}

std::vector<uint8_t> wrap_blob(BlobKind kind, std::span<const uint8_t> body) {
  ByteWriter w;
  for (uint8_t c : kMagic)
    w.u8(c);
  w.u16(kFormatVersion);
  w.u16(static_cast<uint16_t>(kind));
  w.u32(static_cast<uint32_t>(body.size()));
  w.bytes(body);
  return w.take();
}

std::span<const uint8_t> read_blob_header(std::span<const uint8_t> blob, BlobKind expected) {
  ByteReader r(blob, "blob header", "4");
  Header h = parse(blob, r);
  if (h.kind != static_cast<uint16_t>(expected))
    r.fail("blob is a " + blob_kind_name(static_cast<BlobKind>(h.kind)) + " tile, expected " +
           blob_kind_name(expected));
  return blob.subspan(kBlobHeaderSize);
}

BlobKind peek_blob_kind(std::span<const uint8_t> blob) {
  ByteReader r(blob, "blob header", "4");
  return static_cast<BlobKind>(parse(blob, r).kind);
}

}  // namespace tileformat
