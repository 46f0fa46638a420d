// Line, point and area tiles as PNG images (see vector_raster.hpp).
#include "web/vector_raster.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include "runtime/errors.hpp"
#include "runtime/png_codec.hpp"
#include "tileformat/area_tile.hpp"
#include "tileformat/error.hpp"
#include "tileformat/line_tile.hpp"
#include "tileformat/point_tile.hpp"
#include "web/area_mvt.hpp"

namespace globe::web {
namespace {

using tileformat::TileId;

struct Rgb {
  float r = 0, g = 0, b = 0;
};

Rgb parse_color(const std::string& hex) {
  unsigned r = 0, g = 0, b = 0;
  if (hex.size() == 7 && hex[0] == '#') std::sscanf(hex.c_str() + 1, "%2x%2x%2x", &r, &g, &b);
  return {r / 255.0f, g / 255.0f, b / 255.0f};
}

// Premultiplied RGBA in floats; layers of coverage composited one by one.
class Canvas {
 public:
  explicit Canvas(int size) : size_(size), rgba_(size_t(size) * size * 4, 0.0f) {}
  int size() const { return size_; }
  // A new layer (its coverage is the largest of the shapes drawn into it).
  void begin_layer() {
    cover_.assign(size_t(size_) * size_, 0.0f);
    drawn_ = false;
  }
  // A capsule (segment with round ends) of half width `hw` px.
  void segment(double ax, double ay, double bx, double by, double hw) {
    const double reach = hw + 1;
    const int x0 = std::max(0, int(std::floor(std::min(ax, bx) - reach)));
    const int x1 = std::min(size_ - 1, int(std::ceil(std::max(ax, bx) + reach)));
    const int y0 = std::max(0, int(std::floor(std::min(ay, by) - reach)));
    const int y1 = std::min(size_ - 1, int(std::ceil(std::max(ay, by) + reach)));
    const double dx = bx - ax, dy = by - ay, len2 = dx * dx + dy * dy;
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) {
        const double px = x + 0.5 - ax, py = y + 0.5 - ay;
        const double t = len2 > 0 ? std::clamp((px * dx + py * dy) / len2, 0.0, 1.0) : 0.0;
        const double d = std::hypot(px - t * dx, py - t * dy);
        cover(x, y, hw + 0.5 - d);
      }
  }
  void disc(double cx, double cy, double radius) { segment(cx, cy, cx, cy, radius); }
  // The ring between radius r and r + w.
  void ring(double cx, double cy, double r, double w) {
    const int x0 = std::max(0, int(std::floor(cx - r - w - 1))),
              x1 = std::min(size_ - 1, int(std::ceil(cx + r + w + 1)));
    const int y0 = std::max(0, int(std::floor(cy - r - w - 1))),
              y1 = std::min(size_ - 1, int(std::ceil(cy + r + w + 1)));
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) {
        const double d = std::hypot(x + 0.5 - cx, y + 0.5 - cy);
        cover(x, y, std::min(r + w + 0.5 - d, d - r + 0.5));
      }
  }
  // Composites the layer in `color` at `opacity`.
  void end_layer(Rgb color, float opacity) {
    if (!drawn_) return;
    for (size_t i = 0; i < cover_.size(); ++i) {
      const float a = cover_[i] * opacity;
      if (a <= 0) continue;
      float* p = &rgba_[4 * i];
      p[0] = color.r * a + p[0] * (1 - a);
      p[1] = color.g * a + p[1] * (1 - a);
      p[2] = color.b * a + p[2] * (1 - a);
      p[3] = a + p[3] * (1 - a);
    }
  }
  // Adds `cover` (a coverage a pixel) in `color` at `opacity`: fills of
  // polygons that do not overlap, so a pixel two of them share gets the sum
  // of their parts, as one polygon covering it whole (no seam along a shared
  // border, as compositing one over the other would leave).
  void add(const std::vector<float>& cover, Rgb color, float opacity) {
    for (size_t i = 0; i < cover.size(); ++i) {
      const float a = cover[i] * opacity;
      if (a <= 0) continue;
      float* p = &rgba_[4 * i];
      p[0] += color.r * a, p[1] += color.g * a, p[2] += color.b * a, p[3] += a;
      if (p[3] > 1)
        for (int k = 0; k < 4; ++k)
          p[k] /= p[3];
    }
  }
  // Straight-alpha RGBA PNG; empty if nothing was drawn.
  std::vector<uint8_t> png() const {
    std::vector<uint8_t> out(rgba_.size());
    bool any = false;
    for (size_t i = 0; i < rgba_.size(); i += 4) {
      const float a = rgba_[i + 3];
      for (int k = 0; k < 3; ++k)
        out[i + k] =
            uint8_t(std::lround(std::clamp(a > 0 ? rgba_[i + k] / a : 0.0f, 0.0f, 1.0f) * 255));
      out[i + 3] = uint8_t(std::lround(std::clamp(a, 0.0f, 1.0f) * 255));
      any = any || out[i + 3] > 0;
    }
    return any ? encode_png(out.data(), size_, size_, 4, 6) : std::vector<uint8_t>();
  }

 private:
  void cover(int x, int y, double c) {
    if (c <= 0) return;
    float& v = cover_[size_t(y) * size_ + x];
    v = std::max(v, float(std::min(c, 1.0)));
    drawn_ = true;
  }
  int size_;
  std::vector<float> rgba_, cover_;
  bool drawn_ = false;
};

// Polygons filled by the nonzero winding rule on scanlines: kSamples rows of
// samples a pixel, at (j + 0.5) / kSamples, and along each kSamples samples
// a pixel, at (i + 0.5) / kSamples; a pixel's coverage is the share of its
// samples inside. Edges are given one by one (any order, every ring closed);
// fill() adds the coverage of all of them together, so two polygons of one
// fill sharing a border (its edges once each way) leave no seam.
class Scanlines {
 public:
  static constexpr int kSamples = 4;
  explicit Scanlines(int size) : size_(size), rows_(size_t(size) * kSamples) {}
  // The edge from a to b, in pixels (y down).
  void edge(double ax, double ay, double bx, double by) {
    if (ay == by || !std::isfinite(ax + ay + bx + by)) return;
    const int dir = ay < by ? 1 : -1;
    if (ay > by) std::swap(ax, bx), std::swap(ay, by);
    // The sample rows whose centre lies in [ay, by).
    const int n = int(rows_.size());
    const int r0 = int(std::clamp(std::ceil(ay * kSamples - 0.5), 0.0, double(n)));
    const int r1 = int(std::clamp(std::ceil(by * kSamples - 0.5), 0.0, double(n)));
    const double slope = (bx - ax) / (by - ay);
    for (int r = r0; r < r1; ++r) {
      const double y = (r + 0.5) / kSamples;
      rows_[size_t(r)].push_back({ax + (y - ay) * slope, dir});
    }
    if (r0 < r1) low_ = std::min(low_, r0), high_ = std::max(high_, r1);
  }
  // Adds the coverage of the edges given since the last call to `cover`
  // (size² pixels) and forgets them.
  void fill(std::vector<float>& cover) {
    const float w = 1.0f / (kSamples * kSamples);
    const int last = size_ * kSamples;  // samples a row
    for (int r = low_; r < high_; ++r) {
      std::vector<Crossing>& row = rows_[size_t(r)];
      std::sort(row.begin(), row.end(),
                [](const Crossing& a, const Crossing& b) { return a.x < b.x; });
      float* line = &cover[size_t(r / kSamples) * size_];
      int winding = 0;
      for (size_t k = 0; k + 1 < row.size(); ++k) {
        winding += row[k].dir;
        if (winding == 0) continue;
        // The samples whose centre lies in [x_k, x_k+1).
        const int i0 = int(std::clamp(std::ceil(row[k].x * kSamples - 0.5), 0.0, double(last)));
        const int i1 = int(std::clamp(std::ceil(row[k + 1].x * kSamples - 0.5), 0.0, double(last)));
        for (int i = i0; i < i1; ++i)
          line[i / kSamples] += w;
      }
      row.clear();
    }
    low_ = int(rows_.size()), high_ = 0;
  }

 private:
  struct Crossing {
    double x;
    int dir;
  };
  int size_;
  std::vector<std::vector<Crossing>> rows_;  // per sample row
  int low_ = int(rows_.size()), high_ = 0;   // the rows touched
};

// Ground metres per pixel at the centre of tile `id`.
double metres_per_pixel(const tileformat::Tiling& t, TileId id, int size) {
  const tileformat::Bounds b = t.tile_bounds(id);
  const double cy = (b.min_y + b.max_y) / 2, edge = t.tile_size(id.z) / size;
  switch (t.scheme) {
    case tileformat::Scheme::kGeodetic:
      return edge * 111319.49 * std::cos(cy * M_PI / 180);
    case tileformat::Scheme::kWebMercator:
      return edge * std::cos(2 * std::atan(std::exp(cy / 6378137.0)) - M_PI / 2);
    default:
      return edge;
  }
}

}  // namespace

std::vector<uint8_t> line_tile_png(const LinePackage& package, TileId id,
                                   std::span<const uint8_t> blob, int size) {
  tileformat::LineTile t;
  try {
    t = tileformat::decode_line_tile(blob);
  } catch (const tileformat::FormatError& e) {
    throw InputError(package.reader->path() + ": tile " + id.str() + ": " + e.what() +
                     "; check the package with globe-vectorize validate");
  }
  const double px = double(size) / t.extent;  // pixels per tile unit
  const double m_per_px = metres_per_pixel(package.tiling, id, size);
  Canvas canvas(size);
  for (int pass = 0; pass < 2; ++pass)  // every casing, then every fill
    for (size_t c = 0; c < package.classes.size(); ++c) {
      const LineStyle& s = package.classes[c].style;
      const bool casing = !s.casing_color.empty() && s.casing_width > 0;
      if (!s.visible || (pass == 0 && !casing)) continue;
      const double unit = s.width_in_m ? 1 / m_per_px : 1;  // pixels per width unit
      const double hw = std::max(0.5, unit * (s.width / 2 + (pass == 0 ? s.casing_width : 0)));
      canvas.begin_layer();
      for (const tileformat::LineRun& run : t.runs) {
        if (run.class_id != c) continue;
        for (uint32_t v = 0; v + 1 < run.vertex_count; ++v) {
          const tileformat::LineVertex& a = t.vertices[run.first_vertex + v];
          const tileformat::LineVertex& b = t.vertices[run.first_vertex + v + 1];
          canvas.segment(a.x * px, a.y * px, b.x * px, b.y * px, hw);
        }
      }
      for (const tileformat::LinePoint& p : t.points)
        if (p.class_id == c) canvas.disc(p.at.x * px, p.at.y * px, hw);
      const std::string& color = pass == 0         ? s.casing_color
                                 : s.color.empty() ? palette_color(c)
                                                   : s.color;
      canvas.end_layer(parse_color(color), float(s.opacity));
    }
  return canvas.png();
}

std::vector<uint8_t> point_tile_png(
    const PointPackage& package, TileId id,
    const std::function<std::optional<std::vector<uint8_t>>(TileId)>& blob_of, int size) {
  Canvas canvas(size);
  const tileformat::Tiling& tiling = package.meta.common.tiling;
  const Rgb fill = parse_color("#d7301f"), rim{1, 1, 1};
  // The rims (rings outside the radius, as a circle layer's stroke), then
  // the fills.
  for (int pass = 0; pass < 2; ++pass) {
    canvas.begin_layer();
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const int64_t x = int64_t(id.x) + dx, y = int64_t(id.y) + dy;
        if (y < 0 || y >= int64_t(tiling.tiles_y(id.z))) continue;
        const int64_t n = int64_t(tiling.tiles_x(id.z));
        if (!tiling.wraps_x() && (x < 0 || x >= n)) continue;
        const TileId t{id.z, uint32_t((x + n) % n), uint32_t(y)};
        const std::optional<std::vector<uint8_t>> blob = blob_of(t);
        if (!blob) continue;
        tileformat::PointTile tile;
        try {
          tile = tileformat::decode_point_tile(*blob);
        } catch (const tileformat::FormatError& e) {
          throw InputError(package.reader->path() + ": tile " + t.str() + ": " + e.what() +
                           "; check the package with globe-vectorize validate");
        }
        const double px = double(size) / tile.extent;
        for (const tileformat::Place& p : tile.places) {
          const double r =
              std::clamp(3 + (std::sqrt(double(p.count)) - 1) * 27.0 / 99.0, 3.0, 30.0);
          const double cx = p.at.x * px + dx * size, cy = p.at.y * px + dy * size;
          if (pass == 0) {
            canvas.ring(cx, cy, r, 1);
          } else {
            canvas.disc(cx, cy, r);
          }
        }
      }
    canvas.end_layer(pass == 0 ? rim : fill, pass == 0 ? 1.0f : 0.8f);
  }
  return canvas.png();
}

std::vector<uint8_t> area_tile_png(const AreaPackage& package, TileId id,
                                   std::span<const uint8_t> blob, int size) {
  tileformat::AreaTile t;
  try {
    t = tileformat::decode_area_tile(blob);
  } catch (const tileformat::FormatError& e) {
    throw InputError(package.reader->path() + ": tile " + id.str() + ": " + e.what() +
                     "; check the package with globe-vectorize validate");
  }
  const double px = double(size) / t.extent;  // pixels per tile unit
  const std::vector<uint32_t> offsets = t.ring_offsets();
  // Every edge of polygon p's rings (each ring closed).
  auto edges = [&](const tileformat::AreaPolygon& p, const auto& fn) {
    for (uint32_t r = p.first_ring; r < p.first_ring + p.ring_count; ++r)
      for (uint32_t v = offsets[r]; v < offsets[r + 1]; ++v) {
        const tileformat::LineVertex& a = t.vertices[v];
        const tileformat::LineVertex& b = t.vertices[v + 1 < offsets[r + 1] ? v + 1 : offsets[r]];
        fn(a.x * px, a.y * px, b.x * px, b.y * px);
      }
  };
  std::map<uint32_t, std::vector<const tileformat::AreaPolygon*>> by_class;
  for (const tileformat::AreaPolygon& p : t.polygons)
    by_class[p.class_id].push_back(&p);
  Canvas canvas(size);
  Scanlines scan(size);
  std::vector<float> cover;
  // The fills and outlines as area_style_json draws them (area_looks).
  const std::vector<AreaLook> looks = area_looks(package, kAreaWebFillOpacity);
  auto look = [&](uint32_t cls) -> const AreaLook* {
    if (cls < looks.size()) return &looks[cls];
    return package.meta.choropleth ? &looks[0] : nullptr;  // a class it does not list: no data
  };
  for (const auto& [cls, polygons] : by_class) {
    const AreaLook* l = look(cls);
    if (!l || !l->visible) continue;
    for (const tileformat::AreaPolygon* p : polygons)
      edges(*p, [&](double ax, double ay, double bx, double by) { scan.edge(ax, ay, bx, by); });
    cover.assign(size_t(size) * size, 0.0f);
    scan.fill(cover);
    canvas.add(cover, parse_color(l->fill), float(std::min(l->opacity, 1.0)));
  }
  // The outlines over every fill, per class; not along the map's edge (the
  // antimeridian, the poles' rows of a global tiling), where polygons were
  // cut rather than bordered.
  const uint32_t sides = tileformat::map_edge_sides(package.meta.common.tiling, id);
  auto cut = [&](double ax, double ay, double bx, double by) {
    return tileformat::along_map_edge(sides, ax, ay, bx, by, double(size));
  };

  for (const auto& [cls, polygons] : by_class) {
    const AreaLook* l = look(cls);
    if (!l || !l->visible || l->outline_px <= 0) continue;
    canvas.begin_layer();
    for (const tileformat::AreaPolygon* p : polygons)
      edges(*p, [&](double ax, double ay, double bx, double by) {
        if (!cut(ax, ay, bx, by)) canvas.segment(ax, ay, bx, by, l->outline_px / 2);
      });
    canvas.end_layer(parse_color(l->outline), float(kAreaWebFillOpacity));
  }
  return canvas.png();
}

}  // namespace globe::web
