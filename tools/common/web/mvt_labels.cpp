// A package's labels for vector tiles and styles (see mvt_labels.hpp).
#include "web/mvt_labels.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "runtime/errors.hpp"
#include "tileformat/error.hpp"
#include "tileformat/json.hpp"
#include "tileformat/label_table.hpp"

namespace globe::web {
namespace {

constexpr double kPi = 3.14159265358979323846;

// The bits of v at the even positions of the result.
uint64_t spread(uint32_t v) {
  uint64_t x = v;
  x = (x | x << 16) & 0x0000FFFF0000FFFFull;
  x = (x | x << 8) & 0x00FF00FF00FF00FFull;
  x = (x | x << 4) & 0x0F0F0F0F0F0F0F0Full;
  x = (x | x << 2) & 0x3333333333333333ull;
  x = (x | x << 1) & 0x5555555555555555ull;
  return x;
}

uint64_t morton(uint32_t x, uint32_t y) {
  return spread(x) | spread(y) << 1;
}

// A web mercator coordinate 0..1 on the 2^32 grid (the last cell holds 1).
uint32_t grid(double v) {
  return static_cast<uint32_t>(std::clamp(std::floor(v * 4294967296.0), 0.0, 4294967295.0));
}

}  // namespace

MvtLabels::MvtLabels(tileformat::PackageReader& reader) {
  if (!tileformat::has_labels(reader)) return;
  struct Read {
    int64_t id;
    uint64_t feature;
    double priority, lon, lat;
    bool area;
  };
  std::vector<Read> rows;
  try {
    tileformat::LabelTableReader(reader).for_each([&](const tileformat::LabelRecord& r) {
      if (r.feature <= 0) return;
      const uint64_t feature = static_cast<uint64_t>(r.feature);
      if (!text_.emplace(feature, r.text).second) return;  // one label a feature: the first
      rows.push_back({r.id, feature, std::isfinite(r.priority) ? r.priority : 0.0, r.lon, r.lat,
                      r.placement == tileformat::LabelPlacement::kArea});
    });
  } catch (const tileformat::FormatError& e) {
    throw InputError(reader.path() + ": " + e.what() +
                     "; check the package with globe-vectorize validate");
  }
  // Ranks: priority first (larger first), then the labels' own order.
  std::vector<size_t> order(rows.size());
  std::iota(order.begin(), order.end(), size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](size_t a, size_t b) { return rows[a].priority > rows[b].priority; });
  for (size_t k = 0; k < order.size(); ++k) {
    const Read& r = rows[order[k]];
    if (!r.area || !std::isfinite(r.lon) || !std::isfinite(r.lat)) continue;
    Entry e;
    e.feature = r.feature;
    e.rank = static_cast<int64_t>(k) + 1;
    // Longitudes into [-180, 180), latitudes past the mercator's edge onto it.
    const double lon = std::fmod(std::fmod(r.lon + 180.0, 360.0) + 360.0, 360.0) - 180.0;
    const double lat = std::clamp(r.lat, -85.0511287798066, 85.0511287798066);
    e.x = (lon + 180.0) / 360.0;
    e.y = (1.0 - std::asinh(std::tan(lat * kPi / 180.0)) / kPi) / 2.0;
    e.key = morton(grid(e.x), grid(e.y));
    anchors_.push_back(e);
  }
  std::sort(anchors_.begin(), anchors_.end(), [](const Entry& a, const Entry& b) {
    return a.key != b.key ? a.key < b.key : a.rank < b.rank;
  });
}

const std::string* MvtLabels::text(uint64_t feature) const {
  const auto it = text_.find(feature);
  return it == text_.end() ? nullptr : &it->second;
}

std::vector<MvtLabels::Anchor> MvtLabels::anchors_in(tileformat::TileId id, uint32_t extent) const {
  std::vector<Anchor> out;
  if (anchors_.empty() || id.z < 0 || id.z > tileformat::kMaxZoom) return out;
  // The tile's cells on the 2^32 grid are one run of Morton codes.
  const int shift = 2 * (32 - id.z);
  const uint64_t first = shift >= 64 ? 0 : morton(id.x, id.y) << shift;
  const uint64_t last = shift >= 64 ? ~uint64_t{0} : first | ((uint64_t{1} << shift) - 1);
  const auto begin = std::lower_bound(anchors_.begin(), anchors_.end(), first,
                                      [](const Entry& e, uint64_t k) { return e.key < k; });
  const double n = std::ldexp(1.0, id.z);
  for (auto it = begin; it != anchors_.end() && it->key <= last; ++it) {
    const double u = (it->x * n - id.x) * extent, v = (it->y * n - id.y) * extent;
    out.push_back({it->feature,
                   it->rank,
                   {static_cast<int32_t>(std::llround(u)), static_cast<int32_t>(std::llround(v))}});
  }
  std::sort(out.begin(), out.end(),
            [](const Anchor& a, const Anchor& b) { return a.rank < b.rank; });
  return out;
}

void set_name_tag(MvtTags& tags, const std::string& text) {
  MvtValue v;
  v.text = text;
  for (auto& [k, value] : tags)
    if (k == "name") {
      value = v;
      return;
    }
  tags.emplace_back("name", v);
}

std::string style_glyphs_member(const StyleGlyphs& glyphs) {
  if (glyphs.empty()) return "";
  return ",\"glyphs\":\"" + tileformat::json_escape(glyphs.url) + "\"";
}

std::string label_layer_json(const std::string& id, const std::string& source,
                             const std::string& source_layer, const StyleGlyphs& glyphs,
                             const std::string& layout) {
  return "{\"id\":\"" + tileformat::json_escape(id) + "\",\"type\":\"symbol\",\"source\":\"" +
         tileformat::json_escape(source) + "\",\"source-layer\":\"" +
         tileformat::json_escape(source_layer) +
         "\",\"filter\":[\"has\",\"name\"],\"layout\":{\"text-field\":[\"get\",\"name\"],"
         "\"text-font\":[\"" +
         tileformat::json_escape(glyphs.fontstack) + "\"],\"text-size\":12" + layout +
         "},\"paint\":{\"text-color\":\"#222222\",\"text-halo-color\":\"#ffffff\","
         "\"text-halo-width\":1.5}}";
}

}  // namespace globe::web
