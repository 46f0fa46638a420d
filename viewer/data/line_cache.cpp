// Line tile cache (see line_cache.hpp).
#include "data/line_cache.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>

#include "tileformat/line_tile.hpp"

namespace globe::viewer {

using tileformat::TileId;

namespace {

uint32_t float_bits(double v) {
  return std::bit_cast<uint32_t>(static_cast<float>(v));
}

}  // namespace

DecodedLineTile line_tile_words(const tileformat::LineTile& t, const LineHighlight* highlight) {
  DecodedLineTile d;
  d.extent = t.extent;
  d.grid = t.grid;
  d.reach = t.reach;
  d.segments = t.segment_count();
  d.cell_entries = static_cast<uint32_t>(t.cell_segments.size());
  d.words.reserve(t.cell_offsets.size() + t.cell_segments.size() +
                  size_t{d.segments} * kLineWordsPerSegment);
  d.words.insert(d.words.end(), t.cell_offsets.begin(), t.cell_offsets.end());
  d.words.insert(d.words.end(), t.cell_segments.begin(), t.cell_segments.end());
  for (const tileformat::LineRun& r : t.runs) {
    const bool lit =
        highlight && std::binary_search(highlight->features.begin(), highlight->features.end(),
                                        t.feature_ids[r.feature]);
    const uint32_t class_id = lit ? highlight->class_id : r.class_id;
    double along = 0;
    for (uint32_t i = 0; i + 1 < r.vertex_count; ++i) {
      const tileformat::LineVertex a = t.vertices[r.first_vertex + i],
                                   b = t.vertices[r.first_vertex + i + 1];
      d.words.insert(d.words.end(), {float_bits(a.x), float_bits(a.y), float_bits(b.x),
                                     float_bits(b.y), class_id, float_bits(along)});
      const double length = std::hypot(double(b.x) - a.x, double(b.y) - a.y);
      d.longest = std::max(d.longest, static_cast<float>(length));
      along += length;
    }
  }
  return d;
}

std::optional<uint64_t> segment_feature(const tileformat::LineTile& t, uint32_t segment) {
  for (const tileformat::LineRun& r : t.runs) {
    if (segment + 1 < r.vertex_count) return t.feature_ids[r.feature];
    segment -= r.vertex_count - 1;
  }
  return std::nullopt;
}

namespace {

ArenaCacheSource line_source(const std::string& path, const LinePackage& p) {
  return {path,
          p.reader.get(),
          p.tiling,
          p.min_zoom,
          p.max_zoom,
          "line tile",
          "the lines of its coarser or finer tiles are drawn there",
          "--cache-mb"};
}

}  // namespace

LineCache::LineCache(const std::string& path, LinePackage package, uint64_t budget_bytes)
    : ArenaTileCache(line_source(path, package), budget_bytes,
                     [this](TileId, std::span<const uint8_t> blob) {
                       std::shared_ptr<const LineHighlight> h;
                       {
                         std::lock_guard lock(highlight_mutex_);
                         h = highlight_;
                       }
                       return line_tile_words(tileformat::decode_line_tile(blob), h.get());
                     }),
      package_(std::move(package)) {}

LineCache::~LineCache() {
  stop_loader();  // it reads highlight_
}

void LineCache::set_highlight(LineHighlight highlight) {
  std::sort(highlight.features.begin(), highlight.features.end());
  {
    std::lock_guard lock(highlight_mutex_);
    highlight_ = highlight.features.empty()
                     ? nullptr
                     : std::make_shared<const LineHighlight>(std::move(highlight));
  }
  // Tiles decoded with the previous set are dropped, loaded or not.
  forget_all();
}

}  // namespace globe::viewer
