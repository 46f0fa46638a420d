// Fuzz entries (see fuzz_entries.hpp).
#include "fuzz_entries.hpp"

#include <bit>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <fstream>

#include "serve/http_semantics.hpp"
#include "serve/url_route.hpp"
#include "tileformat/analysis_block.hpp"
#include "tileformat/area_tile.hpp"
#include "tileformat/error.hpp"
#include "tileformat/image_tile.hpp"
#include "tileformat/line_tile.hpp"
#include "tileformat/mblock.hpp"
#include "tileformat/metadata.hpp"
#include "tileformat/package.hpp"
#include "tileformat/point_tile.hpp"

namespace globe_fuzz {
namespace {

[[noreturn]] void fail(const char* what) {
  std::fprintf(stderr, "fuzz: %s\n", what);
  std::abort();
}

template <class Fn>
void rejecting_cleanly(Fn&& fn) {
  try {
    fn();
  } catch (const tileformat::FormatError&) {
  } catch (const tileformat::PackageError&) {
  }
}

bool same(const tileformat::MBlock& a, const tileformat::MBlock& b) {
  return a.size == b.size && a.lattice == b.lattice && a.step == b.step && a.q == b.q &&
         a.valid == b.valid && a.vertex_error == b.vertex_error;
}

bool same(const tileformat::LineTile& a, const tileformat::LineTile& b) {
  auto runs = [](const tileformat::LineTile& t) {
    std::vector<uint32_t> v;
    for (const auto& r : t.runs)
      v.insert(v.end(), {r.feature, r.class_id, r.first_vertex, r.vertex_count});
    return v;
  };
  auto vertices = [](const tileformat::LineTile& t) {
    std::vector<int64_t> v;
    for (const auto& p : t.vertices)
      v.insert(v.end(), {p.x, p.y});
    for (const auto& p : t.points)
      v.insert(v.end(), {p.feature, p.class_id, p.at.x, p.at.y});
    return v;
  };
  return a.extent == b.extent && a.grid == b.grid && a.reach == b.reach &&
         a.feature_ids == b.feature_ids && runs(a) == runs(b) && vertices(a) == vertices(b) &&
         a.cell_offsets == b.cell_offsets && a.cell_segments == b.cell_segments;
}

}  // namespace

void mblock(std::span<const uint8_t> data) {
  rejecting_cleanly([&] {
    const tileformat::MBlock m = tileformat::decode_mblock(data);
    tileformat::mblock_stats(m);
    if (!same(tileformat::decode_mblock(
                  tileformat::encode_mblock(m, 1, tileformat::HeightCoding::kBytePlanes)),
              m))
      fail("an MBlock does not survive re-encoding");
  });
}

void image_tile(std::span<const uint8_t> data) {
  rejecting_cleanly([&] {
    const tileformat::ImageHeader h = tileformat::inspect_image_tile(data);
    if (h.width <= 0 || h.height <= 0 || h.channels < 0 || h.channels > 4)
      fail("inspect_image_tile accepted impossible dimensions");
  });
}

void line_tile(std::span<const uint8_t> data) {
  rejecting_cleanly([&] {
    const tileformat::LineTileCounts c = tileformat::peek_line_tile_counts(data);
    const tileformat::LineTile t = tileformat::decode_line_tile(data);
    if (c.segments != t.segment_count() || c.runs != t.runs.size() || c.points != t.points.size() ||
        c.features != t.feature_ids.size())
      fail("peeked line tile counts differ from the decoded tile");
    if (!same(tileformat::decode_line_tile(tileformat::encode_line_tile(t, 1)), t))
      fail("a line tile does not survive re-encoding");
  });
}

void area_tile(std::span<const uint8_t> data) {
  rejecting_cleanly([&] {
    const tileformat::AreaTileCounts c = tileformat::peek_area_tile_counts(data);
    const tileformat::AreaTile t = tileformat::decode_area_tile(data);
    if (c.features != t.feature_ids.size() || c.polygons != t.polygons.size() ||
        c.rings != t.ring_sizes.size() || c.vertices != t.vertices.size())
      fail("peeked area tile counts differ from the decoded tile");
    const tileformat::AreaTile u = tileformat::decode_area_tile(tileformat::encode_area_tile(t, 1));
    auto flat = [](const tileformat::AreaTile& a) {
      std::vector<int64_t> v{a.extent, a.buffer};
      for (uint64_t id : a.feature_ids)
        v.push_back(int64_t(id));
      for (const auto& p : a.polygons)
        v.insert(v.end(), {p.feature, p.class_id, p.first_ring, p.ring_count});
      for (uint32_t n : a.ring_sizes)
        v.push_back(n);
      for (const auto& q : a.vertices)
        v.insert(v.end(), {q.x, q.y});
      return v;
    };
    if (flat(u) != flat(t)) fail("an area tile does not survive re-encoding");
  });
}

void point_tile(std::span<const uint8_t> data) {
  rejecting_cleanly([&] {
    const tileformat::PointTileCounts c = tileformat::peek_point_tile_counts(data);
    const tileformat::PointTile t = tileformat::decode_point_tile(data);
    if (c.places != t.places.size() || c.fields != t.fields ||
        c.cell_entries != t.cell_places.size())
      fail("peeked point tile counts differ from the decoded tile");
    const tileformat::PointTile again =
        tileformat::decode_point_tile(tileformat::encode_point_tile(t, 1));
    auto places = [](const tileformat::PointTile& p) {
      std::vector<int64_t> v;
      for (const auto& pl : p.places)
        v.insert(v.end(), {int64_t(pl.id), pl.count, pl.at.x, pl.at.y});
      return v;
    };
    // Values compare as bits: a NaN must survive as itself.
    auto bits = [](const tileformat::PointTile& p) {
      std::vector<uint32_t> v;
      for (float f : p.values)
        v.push_back(std::bit_cast<uint32_t>(f));
      return v;
    };
    if (again.extent != t.extent || again.grid != t.grid || again.reach != t.reach ||
        places(again) != places(t) || bits(again) != bits(t) ||
        again.cell_offsets != t.cell_offsets || again.cell_places != t.cell_places)
      fail("a point tile does not survive re-encoding");
  });
}

void analysis_block(std::span<const uint8_t> data) {
  rejecting_cleanly([&] {
    const tileformat::AnalysisBlock b = tileformat::decode_analysis_block(data);
    const tileformat::AnalysisBlock again =
        tileformat::decode_analysis_block(tileformat::encode_analysis_block(b, 1));
    if (again.size != b.size || again.layers != b.layers || again.values != b.values)
      fail("an analysis block does not survive re-encoding");
  });
}

void package(std::span<const uint8_t> data, const std::string& scratch_path) {
  {
    std::ofstream out(scratch_path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data.data()),
              static_cast<std::streamsize>(data.size()));
  }
  rejecting_cleanly([&] {
    tileformat::PackageReader r(scratch_path);
    const std::string format = r.meta("format").value_or("");
    r.zoom_summaries();
    r.unique_blobs();
    r.tile({0, 0, 0});
    r.for_each_tile([&](tileformat::TileId, std::span<const uint8_t> blob) {
      if (format == tileformat::kMBlockFormat)
        mblock(blob);
      else if (format == tileformat::kLineClustersFormat)
        line_tile(blob);
      else if (format == tileformat::kPointsFormat)
        point_tile(blob);
      else if (format == tileformat::kAnalysisFormat)
        analysis_block(blob);
      else if (format == tileformat::kAreasFormat)
        area_tile(blob);
      else
        image_tile(blob);
    });
  });
  std::remove(scratch_path.c_str());
}

void url_route(std::span<const uint8_t> data) {
  const std::string path(reinterpret_cast<const char*>(data.data()), data.size());
  const globe::serve::Route r = globe::serve::parse_route(path);
  using Kind = globe::serve::Route::Kind;
  if (r.kind == Kind::kTile && (r.z < 0 || r.z > globe::serve::kMaxZoom || r.name.empty()))
    fail("url_route: a tile route out of range");
  if (r.kind == Kind::kGlyphs &&
      (r.fontstack.empty() || r.fontstack.find('/') != std::string::npos ||
       r.glyph_start % 256 != 0 || r.glyph_start > 0xFF00))
    fail("url_route: a glyph route out of range");
  if (r.kind == Kind::kLibrary) {
    const std::string f = "/" + r.file + "/";
    if (f.find("/../") != std::string::npos || f.find("/./") != std::string::npos ||
        f.find("//") != std::string::npos || f.find('\\') != std::string::npos)
      fail("url_route: a library path that leaves its folder");
  }
  if (r.kind != Kind::kBadRequest && r.kind != Kind::kNotFound && r.kind != Kind::kIndex &&
      r.kind != Kind::kLibrary && r.kind != Kind::kViewer)
    for (char c : r.name)
      if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '_' || c == '-'))
        fail("url_route: a package name with a character outside [A-Za-z0-9._-]");
  // The same bytes as request header values (http_semantics.hpp): ranges
  // always inside the body, never more bytes than it has unless single.
  namespace http = globe::serve::http;
  for (const uint64_t size :
       {uint64_t{0}, uint64_t{1}, uint64_t{6000}, data.size() + uint64_t{1}}) {
    const http::RangeRequest rr = http::parse_range(path, size);
    uint64_t total = 0;
    for (const http::ByteRange& b : rr.ranges) {
      if (b.first > b.last || b.last >= size) fail("http_semantics: a range outside the body");
      total += b.length();
    }
    if (rr.kind == http::RangeRequest::Kind::kRanges &&
        (rr.ranges.empty() || (rr.ranges.size() > 1 && total > size)))
      fail("http_semantics: an empty or amplifying range set");
  }
  http::none_match_fails(path, "\"abc\"");
  http::if_range_holds(path, "\"abc\"", "Sun, 29 Nov 2026 00:00:00 GMT");
  http::accepts_gzip(path);
}

}  // namespace globe_fuzz
