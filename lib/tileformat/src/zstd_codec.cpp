// zstd wrapper (docs/tileformat.md §5).
#include "tileformat/zstd_codec.hpp"

#include <zstd.h>

#include "tileformat/error.hpp"

namespace tileformat {

namespace {
// One context per thread, reused: creating one per call costs more than
// compressing a block (its tables are allocated and cleared every time).
struct Contexts {
  ZSTD_CCtx* c = ZSTD_createCCtx();
  ZSTD_DCtx* d = ZSTD_createDCtx();
  ~Contexts() {
    ZSTD_freeCCtx(c);
    ZSTD_freeDCtx(d);
  }
};
Contexts& contexts() {
  thread_local Contexts ctx;
  return ctx;
}
}  // namespace

std::vector<uint8_t> zstd_compress(std::span<const uint8_t> in, int level, ZstdSearch search) {
  std::vector<uint8_t> out(ZSTD_compressBound(in.size()));
  ZSTD_CCtx* c = contexts().c;
  auto check = [](size_t r) {
    if (ZSTD_isError(r))
      throw std::runtime_error(std::string("zstd compression failed: ") + ZSTD_getErrorName(r));
  };
  check(ZSTD_CCtx_reset(c, ZSTD_reset_session_and_parameters));
  check(ZSTD_CCtx_setParameter(c, ZSTD_c_compressionLevel, level));
  if (search == ZstdSearch::kLazy) {
    check(ZSTD_CCtx_setParameter(c, ZSTD_c_strategy, ZSTD_lazy));
    check(ZSTD_CCtx_setParameter(c, ZSTD_c_minMatch, 4));
  } else if (search == ZstdSearch::kLongMatches) {
    check(ZSTD_CCtx_setParameter(c, ZSTD_c_minMatch, 6));
  }
  const size_t n = ZSTD_compress2(c, out.data(), out.size(), in.data(), in.size());
  check(n);
  out.resize(n);
  return out;
}

std::vector<uint8_t> zstd_decompress(std::span<const uint8_t> in, size_t expected_size,
                                     const std::string& what, const std::string& section) {
  unsigned long long declared = ZSTD_getFrameContentSize(in.data(), in.size());
  if (declared == ZSTD_CONTENTSIZE_ERROR || declared == ZSTD_CONTENTSIZE_UNKNOWN)
    throw FormatError(section, what + ": not a zstd frame with a known size");
  if (declared != expected_size)
    throw FormatError(section, what + ": zstd frame holds " + std::to_string(declared) +
                                   " bytes, expected " + std::to_string(expected_size));
  size_t frame = ZSTD_findFrameCompressedSize(in.data(), in.size());
  if (ZSTD_isError(frame) || frame != in.size())
    throw FormatError(section, what + ": zstd frame is truncated or followed by extra bytes");
  std::vector<uint8_t> out(expected_size);
  size_t n = ZSTD_decompressDCtx(contexts().d, out.data(), out.size(), in.data(), in.size());
  if (ZSTD_isError(n) || n != expected_size)
    throw FormatError(section, what + ": corrupt zstd data (" +
                                   (ZSTD_isError(n) ? ZSTD_getErrorName(n) : "short output") + ")");
  return out;
}

}  // namespace tileformat
