// RFC 9110 applied to one answer, with no I/O and no HTTP library: byte
// ranges (one, a suffix, an open range, several as multipart/byteranges),
// conditional requests (If-None-Match with lists and `*`, If-Range with an
// entity tag or a date), and content coding (gzip, once, for a client that
// accepts it). request_handler.cpp applies them to every answer; the HTTP
// library only moves bytes (docs/serve.md "HTTP").
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace globe::serve::http {

// Inclusive byte positions, first <= last < the representation's size.
struct ByteRange {
  uint64_t first = 0, last = 0;
  uint64_t length() const { return last - first + 1; }
};

struct RangeRequest {
  enum class Kind {
    kWhole,          // no Range, not bytes, or invalid: send the whole body (200)
    kUnsatisfiable,  // valid, but no range overlaps the body (416, bytes */SIZE)
    kRanges,         // one or more ranges, clamped to the body (206)
  };
  Kind kind = Kind::kWhole;
  std::vector<ByteRange> ranges;
};

// A Range header against a body of `size` bytes (RFC 9110 §14.1.1-14.2):
// a last-byte-pos past the end is clamped to size - 1; a suffix range longer
// than the body is the whole body; ranges that do not overlap the body are
// dropped, and if none is left the request is unsatisfiable. Invalid syntax
// (a last-byte-pos below the first, anything but digits, other units) is
// ignored. So is a set of more than `max_ranges` ranges or one asking for
// more bytes than the body has (overlapping ranges repeated to amplify an
// answer): the whole body is cheaper and correct.
RangeRequest parse_range(std::string_view header, uint64_t size, size_t max_ranges = 64);

// "bytes FIRST-LAST/SIZE" and "bytes */SIZE".
std::string content_range(const ByteRange& r, uint64_t size);
std::string unsatisfied_range(uint64_t size);

// If-None-Match (RFC 9110 §13.1.2): `*`, or any listed tag equal to `etag`
// by the weak comparison (W/ prefixes ignored).
bool none_match_fails(std::string_view if_none_match, std::string_view etag);

// If-Range (§13.1.5): true when the Range may be applied: the header holds an
// entity tag strongly equal to `etag` (a weak tag never is), or an HTTP date
// equal to `last_modified` (which must be non-empty).
bool if_range_holds(std::string_view if_range, std::string_view etag,
                    std::string_view last_modified);

// Whether Accept-Encoding allows gzip (§12.5.3): `gzip`, `x-gzip` or `*` with
// a q-value above 0, and gzip not refused by its own q=0.
bool accepts_gzip(std::string_view accept_encoding);

// A multipart/byteranges body (§14.6) of `parts`, each the bytes of the
// matching range of a body of `size` bytes and type `content_type`; returns
// the body and sets `boundary` (one that occurs in no part).
std::string multipart_byteranges(const std::vector<ByteRange>& ranges,
                                 const std::vector<std::string>& parts, uint64_t size,
                                 const std::string& content_type, std::string& boundary);

}  // namespace globe::serve::http
