// The labels of one view (see label_layer.hpp).
#include "app/label_layer.hpp"

#include "app/chart_discs.hpp"
#include "app/label_layout.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <sstream>
#include <unordered_map>
#include <unordered_set>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>

#include "tileformat/json.hpp"

namespace globe::viewer {

namespace {

constexpr float kHaloPx = 1.6f;
constexpr double kShowScale = 0.6;    // legibility cutoff (MapLibre's perspective-ratio cutoff)
constexpr double kKeepScale = 0.55;   // a shown label stays down to this (hysteresis)
constexpr double kMaxScale = 1.4;     // labels near the eye grow no further
constexpr int kMaxNewPerFrame = 400;  // the window's placement budget
constexpr int kRepeatsEachSide = 3;   // line labels: copies either side of the middle
constexpr float kMaxTurnDeg = 45;
constexpr size_t kMaxLinePaths = 1500;  // line labels whose paths a frame projects
constexpr int kCellPx = 48;             // the crowding grid's cells
constexpr uint8_t kPerCell = 4;         // labels laid out per cell a frame (and those shown)

// The ellipsoid's outward normal at lon/lat (degrees), in ECEF axes.
glm::vec3 ecef_up(double lon, double lat) {
  const double l = lon * std::numbers::pi / 180, p = lat * std::numbers::pi / 180;
  return glm::vec3(std::cos(p) * std::cos(l), std::cos(p) * std::sin(l), std::sin(p));
}

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

}  // namespace

LabelLayer::LabelLayer(const std::vector<std::string>& packages, const LabelSettings& settings,
                       const WorldFrame& world, int width, int height)
    : settings_(settings),
      set_(packages, settings.field, settings.font),
      renderer_(width, height),
      placer_(LabelPlacementOptions{width, height}),
      width_(width),
      height_(height) {
  build_probes(world);
}

LabelLayer::~LabelLayer() = default;

void LabelLayer::resize(int width, int height) {
  renderer_.resize(width, height);
  placer_.set_size(width, height);
  width_ = width, height_ = height;
}

void LabelLayer::build_probes(const WorldFrame& world) {
  std::vector<LabelProbe> probes;
  auto probe = [&](std::vector<LabelProbe>& into, double lon, double lat) -> uint32_t {
    if (world.tiling().scheme == tileformat::Scheme::kWebMercator)
      lat = std::clamp(lat, -85.0511, 85.0511);
    glm::dvec2 k;
    try {
      const glm::dvec2 crs = world.lonlat_to_crs(lon, lat);
      k = world.crs_to_key(crs.x, crs.y);
    } catch (const std::exception&) {
      return UINT32_MAX;  // not in this frame's CRS
    }
    if (!std::isfinite(k.x) || !std::isfinite(k.y)) return UINT32_MAX;
    LabelProbe p{};
    p.key[0] = static_cast<int32_t>(std::floor(k.x));
    p.key[1] = static_cast<int32_t>(std::floor(k.y));
    p.frac[0] = static_cast<float>(k.x - std::floor(k.x));
    p.frac[1] = static_cast<float>(k.y - std::floor(k.y));
    into.push_back(p);
    return static_cast<uint32_t>(into.size() - 1);
  };
  for (const LabelEntry& e : set_.labels()) {
    anchor_probe_.push_back(probe(probes, e.record.lon, e.record.lat));
    anchor_up_.push_back(ecef_up(e.record.lon, e.record.lat));
    // A line's path is projected only while its anchor is in view.
    const auto first = static_cast<uint32_t>(path_points_.size());
    uint32_t count = 0;
    for (size_t i = 0; i + 1 < e.record.path.size(); i += 2)
      if (probe(path_points_, e.record.path[i], e.record.path[i + 1]) != UINT32_MAX) {
        path_up_.push_back(ecef_up(e.record.path[i], e.record.path[i + 1]));
        ++count;
      }
    path_probes_.emplace_back(first, count);
  }
  renderer_.set_probes(probes);
}

double LabelLayer::draw(const LayerPass& pass) {
  const auto now = std::chrono::steady_clock::now();
  double dt = first_frame_ ? 0 : std::chrono::duration<double>(now - last_time_).count();
  bool still = false;
  if (pass.loading == Loading::kSettle) {  // headless: a frame is 1/30 s of a camera path
    still = first_frame_ || pass.view.view == last_view_;
    dt = 1.0 / 30;
  }
  last_time_ = now;
  last_view_ = pass.view.view;
  first_frame_ = false;
  placed_.clear();
  candidates_ = occluded_ = illegible_ = 0;
  if (!settings_.enabled || set_.labels().empty()) return renderer_.draw(pass.below_fbo, {}, {});

  const auto t0 = std::chrono::steady_clock::now();
  const View& view = pass.view;
  // GPU passes and their read-backs are timed apart from the CPU's placement.
  double gpu_ms = 0;
  auto timed = [&](auto&& fn) {
    const auto g0 = std::chrono::steady_clock::now();
    auto r = fn();
    gpu_ms +=
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - g0).count();
    return r;
  };
  const std::vector<ProbeResult> probes = timed([&] {
    return renderer_.project(view, pass.world, pass.terrain, pass.heights,
                             pass.shading.exaggeration);
  });
  // The candidates: labels whose anchor is in view, those shown last frame
  // first, then by priority. In the window, where many crowd one spot, only
  // the first kPerCell of each 48 px cell (and every label shown before)
  // are laid out and tested a frame - the placement budget: the work
  // follows what a view can hold, not how many labels it covers, and a cell
  // the crowds leave empty still gets its own labels. Line labels wait
  // beyond kMaxLinePaths a frame (their paths are projected).
  std::vector<LabelEntry>& labels = set_.labels();
  std::unordered_set<uint32_t> shown_before;
  for (uint64_t key : last_placed_keys_)
    shown_before.insert(static_cast<uint32_t>(key >> 4));
  auto on_screen = [&](float x, float y) {
    return x >= 0 && y >= 0 && x < float(width_) && y < float(height_);
  };
  std::vector<uint32_t> in_view;
  for (uint32_t i = 0; i < labels.size(); ++i) {
    if (anchor_probe_[i] == UINT32_MAX) continue;
    const ProbeResult& a = probes[anchor_probe_[i]];
    if (a.front && on_screen(a.x, a.y))
      in_view.push_back(i);  // a label shows while its anchor does
  }
  candidates_ = in_view.size();
  std::vector<char> was_shown(labels.size(), 0);
  for (uint32_t i : shown_before)
    if (i < labels.size()) was_shown[i] = 1;
  std::sort(in_view.begin(), in_view.end(), [&](uint32_t a, uint32_t b) {
    if (was_shown[a] != was_shown[b]) return was_shown[a] > was_shown[b];
    if (labels[a].rank != labels[b].rank) return labels[a].rank > labels[b].rank;
    return a < b;
  });
  // The window only: a headless picture places every candidate.
  const bool crowd_cap = pass.loading == Loading::kAsReady;
  const int cols = width_ / kCellPx + 1, rows = height_ / kCellPx + 1;
  std::vector<uint8_t> crowd(size_t(cols) * size_t(rows), 0);
  std::vector<uint32_t> admitted;
  size_t lines = 0;
  for (uint32_t i : in_view) {
    const ProbeResult& a = probes[anchor_probe_[i]];
    uint8_t& n = crowd[size_t(int(a.y) / kCellPx) * size_t(cols) + size_t(int(a.x) / kCellPx)];
    if (crowd_cap && !was_shown[i] && n >= kPerCell) continue;
    const bool line = path_probes_[i].second >= 2;
    if (line && lines >= kMaxLinePaths) continue;
    n = uint8_t(std::min(255, n + 1));
    lines += line ? 1 : 0;
    admitted.push_back(i);
  }
  std::sort(admitted.begin(), admitted.end());  // label order, as before: deterministic bids
  std::vector<LabelProbe> path_in;
  std::vector<uint32_t> path_base(set_.labels().size(), UINT32_MAX);
  for (uint32_t i : admitted) {
    const auto [first, count] = path_probes_[i];
    if (count < 2) continue;
    path_base[i] = static_cast<uint32_t>(path_in.size());
    path_in.insert(path_in.end(), path_points_.begin() + first,
                   path_points_.begin() + first + count);
  }
  const std::vector<ProbeResult> path_at_screen = timed([&] {
    return renderer_.project(path_in, view, pass.world, pass.terrain, pass.heights,
                             pass.shading.exaggeration);
  });
  // The distance labels have their nominal size at: the ground at the
  // view's centre (else the median anchor in view).
  double d_ref = timed([&] {
    return renderer_.terrain_distances({float(width_) / 2, float(height_) / 2}, pass.g, view)[0];
  });
  if (!(d_ref > 0)) {
    std::vector<float> d;
    for (const ProbeResult& p : probes)
      if (p.front && p.x >= 0 && p.y >= 0 && p.x < width_ && p.y < height_) d.push_back(p.distance);
    if (d.empty()) d.push_back(float(glm::length(view.eye)));
    std::nth_element(d.begin(), d.begin() + long(d.size() / 2), d.end());
    d_ref = d[d.size() / 2];
  }
  const float focal = static_cast<float>(view.pixels_per_radian);
  const float pad = 100;  // a line's path may reach this far past the screen's edge
  // The legends and charts: no label covers one, and a place's label goes
  // beside its chart.
  std::vector<ScreenBox> obstacles;
  for (const SceneLayer* layer : below_)
    for (const glm::vec4& b : layer->overlay_boxes())
      obstacles.push_back({b.x, b.y, b.z, b.w});
  ChartDiscs discs;
  if (charts_) {
    std::vector<LabelProbe> places;
    std::vector<float> radii;
    for (const ChartLayer::Mark& m : charts_->marks()) {
      places.push_back({{m.key[0], m.key[1]}, {m.frac[0], m.frac[1]}});
      radii.push_back(m.radius_px);
    }
    const std::vector<ProbeResult> at = timed([&] {
      return renderer_.project(places, view, pass.world, pass.terrain, pass.heights,
                               pass.shading.exaggeration);
    });
    for (size_t c = 0; c < at.size(); ++c)
      if (at[c].front && radii[c] > 0) discs.add(at[c].x, at[c].y, radii[c]);
    const std::vector<ScreenBox> charts = discs.obstacles();
    obstacles.insert(obstacles.end(), charts.begin(), charts.end());
  }

  // Each candidate's layouts and the pixels to test them at.
  const SightLines sight(view);
  // The ground's up in the world: the ellipsoid's normal turned into the
  // view's east-north-up frame on the globe; straight up on the flat frame.
  const glm::dmat3 enu = pass.world.globe() ? pass.world.anchor(view.origin).enu : glm::dmat3(0.0);
  auto up_of = [&](const glm::vec3& ecef) {
    return pass.world.globe() ? glm::normalize(enu * glm::dvec3(ecef)) : glm::dvec3(0, 0, 1);
  };
  std::vector<LabelLayout> lays;
  LabelSamples samples;
  std::vector<ScreenPathPoint> path;
  for (uint32_t i : admitted) {
    const ProbeResult& a = probes[anchor_probe_[i]];
    LabelEntry& e = labels[i];
    const ShapedLabel& s = set_.shaped(e);
    if (!s.ok) continue;
    // Sized by distance (MapLibre's perspective ratio), areas a little larger.
    const double sd = std::min(kMaxScale, 0.5 + 0.5 * d_ref / std::max(a.distance, 1e-3f));
    const bool area = e.record.placement == tileformat::LabelPlacement::kArea;
    LabelText t{s};
    t.size = static_cast<float>(settings_.size_px * (area ? 1.1 : 1.0) * sd);
    t.k = t.size / LabelSet::kAtlasPx;
    t.width = s.width * t.k, t.ascent = s.ascent * t.k, t.descent = s.descent * t.k;
    const size_t first_layout = lays.size();
    const auto [first, count] = path_probes_[i];
    if (count < 2) {
      const float chart_r = area ? 0.f : discs.radius_at(a.x, a.y);
      lays.push_back(
          lay_out_at_anchor(i, t, a, area, chart_r, up_of(anchor_up_[i]), sight, samples));
    } else {
      if (path_base[i] == UINT32_MAX) continue;  // deferred to a later frame
      // The first stretch of the path on the near side, in and around the view.
      path.clear();
      for (uint32_t p = first; p < first + count; ++p) {
        const ProbeResult& q = path_at_screen[path_base[i] + (p - first)];
        if (!q.front || !(q.x > -pad && q.y > -pad && q.x < width_ + pad && q.y < height_ + pad)) {
          if (path.size() >= 2) break;
          path.clear();
          continue;
        }
        const float along =
            path.empty() ? 0 : path.back().s + std::hypot(q.x - path.back().x, q.y - path.back().y);
        path.push_back({q.x, q.y, along, q.distance, p});
      }
      lay_out_along_path(
          i, t, a, path, kRepeatsEachSide, kMaxTurnDeg,
          [&](uint32_t point) { return up_of(path_up_[point]); }, sight, samples, lays);
    }
    for (size_t l = first_layout; l < lays.size(); ++l)
      lays[l].legible = sd >= kShowScale;
  }

  // The terrain's distance at every sample: a label whose samples see
  // terrain nearer than the label is behind it.
  const std::vector<float> terrain =
      timed([&] { return renderer_.terrain_distances(samples.xy, pass.g, view); });
  const std::unordered_set<uint64_t> drawn_before(last_placed_keys_.begin(),
                                                  last_placed_keys_.end());
  std::vector<LabelBid> bids(lays.size());
  for (size_t b = 0; b < lays.size(); ++b) {
    const LabelLayout& l = lays[b];
    const bool before = drawn_before.count(l.key) != 0;
    auto behind = [&](size_t sample) {
      const float t = terrain[l.sample_first + sample];
      // Terrain hides a label where it is nearer than the label itself and
      // rises above the ground's plane there (so that neither the ground
      // falling towards the eye on a globe nor a slope behind the label
      // counts).
      const float d = l.along_line ? l.expected[sample] : std::min(l.expected[sample], l.distance);
      if (l.expected[sample] < 0) return false;  // the sight line misses the ground's plane
      // Hysteresis: a shown label needs more terrain in front to go.
      const float tol = d * (before ? 0.015f : 0.008f) + d * (before ? 4.f : 2.f) / focal;
      return t >= 0 && t < d - tol;
    };
    bool hidden = false;
    std::vector<char> clear;
    if (l.shifts.size() > 1) {  // the anchor, then 3 samples per place
      hidden = behind(0);
      for (size_t sh = 0; sh < l.shifts.size(); ++sh)
        clear.push_back(!behind(1 + 3 * sh) && !behind(2 + 3 * sh) && !behind(3 + 3 * sh));
      hidden = hidden || std::find(clear.begin(), clear.end(), 1) == clear.end();
    } else {
      for (size_t sm = 0; sm < l.sample_count && !hidden; ++sm)
        hidden = behind(sm);
    }
    occluded_ += hidden ? 1 : 0;
    LabelBid& bid = bids[b];
    bid.key = l.key;
    bid.priority = labels[l.label].rank;
    bid.boxes = l.boxes;
    bid.shifts = l.shifts;
    bid.clear = std::move(clear);
    bid.drawable = !hidden;
    bid.legible = l.legible ||
                  (before && l.scale * LabelSet::kAtlasPx >= float(settings_.size_px * kKeepScale));
    illegible_ += bid.legible ? 0 : 1;
  }
  const std::vector<LabelPlace> placed = placer_.place(
      bids, dt, still, pass.loading == Loading::kAsReady ? kMaxNewPerFrame : -1, obstacles);

  // The glyphs of the labels shown.
  std::vector<GlyphQuad> quads;
  last_placed_keys_.clear();
  for (size_t b = 0; b < lays.size(); ++b) {
    if (placed[b].alpha <= 0) continue;
    const LabelLayout& l = lays[b];
    const BoxShift sh = l.shifts[size_t(placed[b].shift)];
    const float alpha = placed[b].alpha;
    last_placed_keys_.push_back(l.key);
    const ShapedLabel& s = *labels[l.label].shaped;
    Placed p{l.label,
             {l.box.x0 + sh.dx, l.box.y0 + sh.dy, l.box.x1 + sh.dx, l.box.y1 + sh.dy},
             alpha,
             {}};
    const bool line = l.pivots.size() == s.glyphs.size() &&
                      labels[l.label].record.placement == tileformat::LabelPlacement::kLine &&
                      path_probes_[l.label].second >= 2;
    for (size_t g = 0; g < s.glyphs.size(); ++g) {
      const LabelGlyph& lg = s.glyphs[g];
      const auto& pv = l.pivots[g];
      if (line) p.glyphs.push_back({pv[0], pv[1], pv[2] * 180 / std::numbers::pi_v<float>});
      if (!lg.atlas) continue;
      const text::GlyphAtlas::Entry& en = *lg.atlas;
      GlyphQuad q{};
      q.pivot[0] = pv[0] + sh.dx, q.pivot[1] = pv[1] + sh.dy, q.pivot[2] = pv[2];
      q.pivot[3] = l.scale;
      // Line glyphs pivot about their centre on the line; straight ones
      // about their pen position on the baseline.
      const float x0 = line ? en.left * l.scale - lg.advance / 2 * l.scale : en.left * l.scale;
      const float y0 = l.baseline - (en.top + (line ? lg.y : 0)) * l.scale;
      q.rect[0] = x0, q.rect[1] = y0;
      q.rect[2] = x0 + en.width * l.scale, q.rect[3] = y0 + en.height * l.scale;
      q.atlas[0] = float(en.x), q.atlas[1] = float(en.y);
      q.atlas[2] = float(en.x + en.width), q.atlas[3] = float(en.y + en.height);
      q.style[0] = alpha, q.style[1] = kHaloPx;
      quads.push_back(q);
    }
    placed_.push_back(std::move(p));
  }
  text::GlyphAtlas& atlas = set_.atlas();
  if (const auto [y0, y1] = atlas.dirty_rows(); y1 > y0 || first_upload_) {
    renderer_.upload_atlas(atlas.pixels().data(), atlas.width(), atlas.height(), y0, y1);
    atlas.clear_dirty();
    first_upload_ = false;
  }
  probe_ms_ = gpu_ms;
  place_ms_ =
      -gpu_ms +
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return renderer_.draw(pass.below_fbo, quads, LabelColors{});
}

std::string LabelLayer::frame_json() const {
  std::ostringstream o;
  o << "{\"candidates\": " << candidates_ << ", \"shown\": " << placed_.size()
    << ", \"occluded\": " << occluded_ << ", \"illegible\": " << illegible_ << ", \"labels\": [";
  const std::vector<LabelEntry>& labels = set_.labels();
  for (size_t i = 0; i < placed_.size(); ++i) {
    const Placed& p = placed_[i];
    const LabelEntry& e = labels[p.label];
    const char* kind = e.record.placement == tileformat::LabelPlacement::kArea   ? "area"
                       : e.record.placement == tileformat::LabelPlacement::kLine ? "line"
                                                                                 : "point";
    o << (i ? ", " : "") << "{\"text\": \"" << tileformat::json_escape(e.record.text)
      << "\", \"placement\": \"" << kind << "\", \"source\": {\"package\": \""
      << tileformat::json_escape(set_.sources()[e.source])
      << "\", \"feature\": " << e.record.feature << ", \"label\": " << e.record.id
      << "}, \"anchor\": [" << number(e.record.lon) << ", " << number(e.record.lat)
      << "], \"box\": [" << number(p.box.x0) << ", " << number(p.box.y0) << ", " << number(p.box.x1)
      << ", " << number(p.box.y1) << "], \"alpha\": " << number(p.alpha);
    if (!p.glyphs.empty()) {
      o << ", \"glyphs\": [";
      for (size_t g = 0; g < p.glyphs.size(); ++g)
        o << (g ? ", " : "") << "[" << number(p.glyphs[g][0]) << ", " << number(p.glyphs[g][1])
          << ", " << number(p.glyphs[g][2]) << "]";
      o << "]";
    }
    o << "}";
  }
  o << "]}";
  return o.str();
}

std::string LabelLayer::stats_json(double ms) const {
  std::ostringstream o;
  o << ", \"labels\": {\"stored\": " << set_.labels().size() << ", \"candidates\": " << candidates_
    << ", \"shown\": " << placed_.size() << ", \"occluded\": " << occluded_
    << ", \"illegible\": " << illegible_ << ", \"place_ms\": " << number(place_ms_)
    << ", \"probe_ms\": " << number(probe_ms_) << ", \"glyphs\": "
    << (set_.labels().empty() ? 0 : const_cast<LabelSet&>(set_).atlas().glyph_count())
    << ", \"ms\": " << number(ms) << "}";
  return o.str();
}

}  // namespace globe::viewer
