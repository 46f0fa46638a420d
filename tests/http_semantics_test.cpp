// globe-serve's RFC 9110 rules without a network: the expectations are the
// RFC's own examples and sentences (section numbers beside them), not the
// code's. The same rules through real clients: tests/http_conformance/.
#include <gtest/gtest.h>

#include "serve/http_semantics.hpp"

namespace {

using globe::serve::http::accepts_gzip;
using globe::serve::http::ByteRange;
using globe::serve::http::if_range_holds;
using globe::serve::http::multipart_byteranges;
using globe::serve::http::none_match_fails;
using globe::serve::http::parse_range;
using globe::serve::http::RangeRequest;
using Kind = RangeRequest::Kind;

std::vector<std::pair<uint64_t, uint64_t>> spans(const RangeRequest& r) {
  std::vector<std::pair<uint64_t, uint64_t>> out;
  for (const ByteRange& b : r.ranges)
    out.emplace_back(b.first, b.last);
  return out;
}

using Spans = std::vector<std::pair<uint64_t, uint64_t>>;

// §14.1.2's examples, on a representation of 10000 bytes.
TEST(HttpSemantics, RangeExamplesOfRfc9110) {
  EXPECT_EQ(spans(parse_range("bytes=0-499", 10000)), (Spans{{0, 499}}));
  EXPECT_EQ(spans(parse_range("bytes=500-999", 10000)), (Spans{{500, 999}}));
  EXPECT_EQ(spans(parse_range("bytes=-500", 10000)), (Spans{{9500, 9999}}));
  EXPECT_EQ(spans(parse_range("bytes=9500-", 10000)), (Spans{{9500, 9999}}));
  EXPECT_EQ(spans(parse_range("bytes=0-0,-1", 10000)), (Spans{{0, 0}, {9999, 9999}}));
  EXPECT_EQ(spans(parse_range("bytes= 0-999, 4500-5499, -1000", 10000)),
            (Spans{{0, 999}, {4500, 5499}, {9000, 9999}}));
  EXPECT_EQ(spans(parse_range("bytes=500-600,601-999", 10000)), (Spans{{500, 600}, {601, 999}}));
  EXPECT_EQ(spans(parse_range("bytes=500-700,601-999", 10000)), (Spans{{500, 700}, {601, 999}}));
}

// §14.1.2: "If the last-pos value is absent, or if the value is greater than
// or equal to the current length of the representation data, the byte range
// is interpreted as the remainder of the representation"; a suffix longer
// than the representation is all of it.
TEST(HttpSemantics, RangesPastTheEndAreClamped) {
  EXPECT_EQ(spans(parse_range("bytes=586975-587085", 586985)), (Spans{{586975, 586984}}));
  EXPECT_EQ(spans(parse_range("bytes=0-16383", 6000)), (Spans{{0, 5999}}));
  EXPECT_EQ(spans(parse_range("bytes=-20000", 6000)), (Spans{{0, 5999}}));
  EXPECT_EQ(spans(parse_range("bytes=100-", 6000)), (Spans{{100, 5999}}));
  EXPECT_EQ(spans(parse_range("bytes=0-99999999999999999999999", 6000)), (Spans{{0, 5999}}));
  EXPECT_EQ(parse_range("Bytes=0-1", 10).kind, Kind::kRanges) << "the unit is case-insensitive";
}

// §14.1.1: a range-set is satisfiable when some int-range starts before the
// end or some suffix-range is non-empty; else 416 (§15.5.17). Unsatisfiable
// members beside satisfiable ones are dropped.
TEST(HttpSemantics, UnsatisfiableRanges) {
  EXPECT_EQ(parse_range("bytes=6000-", 6000).kind, Kind::kUnsatisfiable);
  EXPECT_EQ(parse_range("bytes=6005-6010", 6000).kind, Kind::kUnsatisfiable);
  EXPECT_EQ(parse_range("bytes=99999999999999999999-", 6000).kind, Kind::kUnsatisfiable);
  EXPECT_EQ(parse_range("bytes=-0", 6000).kind, Kind::kUnsatisfiable);
  EXPECT_EQ(parse_range("bytes=0-", 0).kind, Kind::kUnsatisfiable);
  EXPECT_EQ(parse_range("bytes=-5", 0).kind, Kind::kUnsatisfiable);
  EXPECT_EQ(spans(parse_range("bytes=7000-7100,0-9", 6000)), (Spans{{0, 9}}));
  EXPECT_EQ(globe::serve::http::unsatisfied_range(63229), "bytes */63229");
  EXPECT_EQ(globe::serve::http::content_range({63219, 63228}, 63229), "bytes 63219-63228/63229");
}

// §14.2: "A server MAY ignore the Range header field"; an invalid one
// (last-pos below first-pos, §14.1.1; not the bytes unit; not the grammar)
// is answered with the whole representation. So are sets that would
// amplify the answer (overlaps asking for more than the body, too many).
TEST(HttpSemantics, InvalidOrAbusiveRangesGetTheWholeBody) {
  for (const char* bad : {"bytes=5-2", "bytes=abc", "items=0-5", "bytes=", "bytes=,", "bytes=1",
                          "bytes=0x1-2", "bytes=-", "bytes=1-2-3", "bytes=5-2,junk", "0-5"})
    EXPECT_EQ(parse_range(bad, 6000).kind, Kind::kWhole) << bad;
  EXPECT_EQ(parse_range("bytes=0-5999,0-5999", 6000).kind, Kind::kWhole);
  std::string many = "bytes=";
  for (int i = 0; i < 100; ++i)
    many += std::to_string(i) + "-" + std::to_string(i) + ",";
  EXPECT_EQ(parse_range(many, 6000).kind, Kind::kWhole);
}

// §13.1.2: If-None-Match uses the weak comparison; `*` matches any current
// representation; a list matches if any member does.
TEST(HttpSemantics, IfNoneMatch) {
  EXPECT_TRUE(none_match_fails("\"abc\"", "\"abc\""));
  EXPECT_TRUE(none_match_fails("W/\"abc\"", "\"abc\""));
  EXPECT_TRUE(none_match_fails("\"abc\"", "W/\"abc\""));
  EXPECT_TRUE(none_match_fails("\"x\", \"abc\" ,\"y\"", "\"abc\""));
  EXPECT_TRUE(none_match_fails("*", "\"abc\""));
  EXPECT_TRUE(none_match_fails("\"a,b\", \"abc\"", "\"abc\"")) << "a comma inside a tag";
  EXPECT_FALSE(none_match_fails("\"abd\"", "\"abc\""));
  EXPECT_FALSE(none_match_fails("", "\"abc\""));
  EXPECT_FALSE(none_match_fails("\"abc", "\"abc\"")) << "malformed";
  EXPECT_FALSE(none_match_fails("\"abc\"-gz", "\"abc\""));
}

// §13.1.5: If-Range with an entity tag holds only under the strong
// comparison; with a date only if it equals Last-Modified exactly.
TEST(HttpSemantics, IfRange) {
  const std::string tag = "\"1f-2a\"", date = "Sun, 29 Nov 2026 00:00:00 GMT";
  EXPECT_TRUE(if_range_holds("", tag, date));
  EXPECT_TRUE(if_range_holds(tag, tag, date));
  EXPECT_FALSE(if_range_holds("\"stale\"", tag, date));
  EXPECT_FALSE(if_range_holds("W/" + tag, tag, date)) << "a weak tag never matches";
  EXPECT_FALSE(if_range_holds(tag, "W/" + tag, date));
  EXPECT_TRUE(if_range_holds(date, tag, date));
  EXPECT_FALSE(if_range_holds("Thu, 01 Jan 1970 00:00:00 GMT", tag, date));
  EXPECT_FALSE(if_range_holds(date, tag, "")) << "no Last-Modified: a date never matches";
}

// §12.5.3: a coding is acceptable with q > 0; `*` stands for codings not
// listed; q=0 refuses.
TEST(HttpSemantics, AcceptEncoding) {
  EXPECT_TRUE(accepts_gzip("gzip"));
  EXPECT_TRUE(accepts_gzip("deflate, gzip;q=0.5, br"));
  EXPECT_TRUE(accepts_gzip("x-gzip"));
  EXPECT_TRUE(accepts_gzip("GZIP"));
  EXPECT_TRUE(accepts_gzip("*"));
  EXPECT_FALSE(accepts_gzip(""));
  EXPECT_FALSE(accepts_gzip("br, deflate"));
  EXPECT_FALSE(accepts_gzip("gzip;q=0"));
  EXPECT_FALSE(accepts_gzip("gzip; q=0.000"));
  EXPECT_FALSE(accepts_gzip("*, gzip;q=0"));
  EXPECT_FALSE(accepts_gzip("identity"));
}

// §14.6: each part with its Content-Type and Content-Range (the whole
// representation's length after the slash), the boundary absent from the
// parts, the closing delimiter last.
TEST(HttpSemantics, MultipartByteranges) {
  std::string boundary;
  const std::string body = multipart_byteranges({{0, 2}, {7, 9}}, {"abc", "hij"}, 10,
                                                "application/vnd.pmtiles", boundary);
  ASSERT_FALSE(boundary.empty());
  EXPECT_EQ(body, "\r\n--" + boundary +
                      "\r\nContent-Type: application/vnd.pmtiles\r\nContent-Range: bytes 0-2/10"
                      "\r\n\r\nabc\r\n--" +
                      boundary +
                      "\r\nContent-Type: application/vnd.pmtiles\r\nContent-Range: bytes 7-9/10"
                      "\r\n\r\nhij\r\n--" +
                      boundary + "--\r\n");
  // A part holding the first boundary's text gets another boundary.
  const std::string clash = boundary;
  multipart_byteranges({{0, 2}, {7, 9}}, {clash, "hij"}, 10, "x/y", boundary);
  EXPECT_NE(boundary, clash);
}

}  // namespace
