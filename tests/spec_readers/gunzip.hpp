// gzip (RFC 1952) via zlib for the spec readers: windowBits 16 + MAX_WBITS
// accepts only a gzip wrapper, and the whole input must be exactly one gzip
// member. Errors throw std::runtime_error("<prefix><what>: ...").
#pragma once

#include <zlib.h>

#include <cstddef>
#include <stdexcept>
#include <string>
#include <string_view>

namespace spec_readers {

inline std::string gunzip(std::string_view in, const std::string& prefix, std::size_t max_output) {
  auto fail = [&](const std::string& why) { throw std::runtime_error(prefix + why); };
  z_stream zs{};
  if (inflateInit2(&zs, 16 + MAX_WBITS) != Z_OK) fail("zlib inflateInit2 failed");
  zs.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(in.data()));
  zs.avail_in = static_cast<uInt>(in.size());
  std::string out;
  char buffer[1 << 15];
  int rc = Z_OK;
  while (rc != Z_STREAM_END) {
    zs.next_out = reinterpret_cast<Bytef*>(buffer);
    zs.avail_out = sizeof buffer;
    rc = inflate(&zs, Z_NO_FLUSH);
    if (rc != Z_OK && rc != Z_STREAM_END) {
      const std::string reason = rc == Z_BUF_ERROR ? "truncated" : (zs.msg ? zs.msg : "corrupt");
      const auto at = zs.total_in;
      inflateEnd(&zs);
      fail("gzip data " + reason + " (at compressed byte " + std::to_string(at) + ")");
    }
    out.append(buffer, sizeof buffer - zs.avail_out);
    if (out.size() > max_output) {
      inflateEnd(&zs);
      fail("gzip data inflates to more than " + std::to_string(max_output) + " bytes");
    }
  }
  const auto left = zs.avail_in;
  inflateEnd(&zs);
  if (left != 0) fail(std::to_string(left) + " trailing bytes after the gzip stream");
  return out;
}

}  // namespace spec_readers
