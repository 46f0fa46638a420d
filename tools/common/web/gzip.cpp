// gzip through zlib (see gzip.hpp).
#include "web/gzip.hpp"

#include <zlib.h>

#include <stdexcept>

namespace globe::web {

std::vector<uint8_t> gzip(std::span<const uint8_t> bytes, int level) {
  z_stream z{};
  // windowBits 15 + 16: a gzip header and trailer; zlib writes mtime 0 and
  // no name, so equal input gives equal output.
  if (deflateInit2(&z, level, Z_DEFLATED, 15 + 16, 8, Z_DEFAULT_STRATEGY) != Z_OK)
    throw std::runtime_error("gzip: zlib cannot start");
  std::vector<uint8_t> out(deflateBound(&z, static_cast<uLong>(bytes.size())) + 32);
  z.next_in = const_cast<Bytef*>(bytes.data());
  z.avail_in = static_cast<uInt>(bytes.size());
  z.next_out = out.data();
  z.avail_out = static_cast<uInt>(out.size());
  const int r = deflate(&z, Z_FINISH);
  const size_t n = out.size() - z.avail_out;
  deflateEnd(&z);
  if (r != Z_STREAM_END) throw std::runtime_error("gzip: zlib failed");
  out.resize(n);
  return out;
}

}  // namespace globe::web
