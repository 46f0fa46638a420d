// What each fuzz target does with one input, shared by the libFuzzer targets
// (tests/fuzz/fuzz_*.cpp, scripts/fuzz.sh) and the regression test that
// replays every saved input (tests/fuzz_regression_test.cpp). Each entry
// feeds the bytes to a decoder; a clean rejection (tileformat::FormatError or
// PackageError) is fine, anything else (another exception, a crash, a
// sanitizer report, a decoded value that does not survive re-encoding)
// aborts.
#pragma once

#include <cstdint>
#include <span>
#include <string>

namespace globe_fuzz {

// decode_mblock; what decodes must re-encode and decode to the same block.
void mblock(std::span<const uint8_t> data);
// inspect_image_tile (the image blob's header).
void image_tile(std::span<const uint8_t> data);
// decode_line_tile and peek_line_tile_counts; decoded tiles must re-encode
// and decode to the same tile, and the peeked counts must match.
void line_tile(std::span<const uint8_t> data);
// decode_point_tile and peek_point_tile_counts, as for line tiles.
void point_tile(std::span<const uint8_t> data);
// decode_area_tile and peek_area_tile_counts, as for line tiles.
void area_tile(std::span<const uint8_t> data);
// decode_analysis_block; what decodes must re-encode and decode to the
// same block.
void analysis_block(std::span<const uint8_t> data);
// The bytes as a request path for globe-serve's parse_route: never throws;
// a tile route has a zoom <= 30 and a valid name; a library path has no
// "." or ".." segment; anything else is a 400 or 404. The same bytes as
// request header values (Range, If-None-Match, If-Range, Accept-Encoding):
// ranges inside the body, never an amplifying set.
void url_route(std::span<const uint8_t> data);
// The bytes as a package file at `scratch_path`: open, read the metadata,
// summaries, and every tile, decoding it by the package's format.
void package(std::span<const uint8_t> data, const std::string& scratch_path);

}  // namespace globe_fuzz
