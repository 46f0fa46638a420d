// The labels of one view (see label_layer.hpp).
#include "app/label_layer.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <sstream>
#include <unordered_map>
#include <unordered_set>

#include <glm/geometric.hpp>
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

struct PathPoint {
  float x, y, s, d;  // screen px, arc length px, distance
  uint32_t probe;    // its probe
};

// Position, direction and distance at arc length s of a screen path.
struct PathAt {
  float x, y, angle, d;
};
PathAt path_at(const std::vector<PathPoint>& p, float s) {
  size_t i = 1;
  while (i + 1 < p.size() && p[i].s < s)
    ++i;
  const PathPoint& a = p[i - 1];
  const PathPoint& b = p[i];
  const float len = std::max(b.s - a.s, 1e-6f);
  const float t = std::clamp((s - a.s) / len, 0.f, 1.f);
  return {a.x + (b.x - a.x) * t, a.y + (b.y - a.y) * t, std::atan2(b.y - a.y, b.x - a.x),
          a.d + (b.d - a.d) * t};
}

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

}  // namespace

// One bid's geometry: where its glyphs go and what it covers.
struct LabelLayer::Layout {
  uint32_t label = 0;
  uint64_t key = 0;
  float scale = 1;     // screen px per atlas texel
  float distance = 0;  // of its anchor (expected depth of the samples)
  bool legible = true;
  std::vector<std::array<float, 3>> pivots;  // per glyph: x, y, angle (radians)
  float baseline = 0;                        // of the glyphs, px below their pivot
  ScreenBox box;
  std::vector<ScreenBox> boxes;
  std::vector<BoxShift> shifts = {BoxShift{}};  // the places it may take
  bool along_line = false;                      // glyphs on a line's path
  size_t sample_first = 0, sample_count = 0;
  std::vector<float> expected;  // per sample: the label's distance there
};

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
  glm::dvec2 last_key{0, 0};
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
    last_key = k;
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
    anchor_key_.push_back(last_key);
    // A line's path is projected only while its anchor is in view.
    const auto first = static_cast<uint32_t>(path_points_.size());
    uint32_t count = 0;
    for (size_t i = 0; i + 1 < e.record.path.size(); i += 2)
      if (probe(path_points_, e.record.path[i], e.record.path[i + 1]) != UINT32_MAX) {
        path_keys_.push_back(last_key);
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
  // The paths of the line labels whose anchor is in view: those shown last
  // frame, then by priority, at most kMaxLinePaths (the rest wait).
  std::vector<uint32_t> lines_in_view;
  std::unordered_set<uint32_t> shown_lines;
  for (uint64_t key : last_placed_keys_)
    shown_lines.insert(static_cast<uint32_t>(key >> 4));
  for (uint32_t i = 0; i < set_.labels().size(); ++i) {
    if (path_probes_[i].second < 2 || anchor_probe_[i] == UINT32_MAX) continue;
    const ProbeResult& a = probes[anchor_probe_[i]];
    if (a.front && a.x >= 0 && a.y >= 0 && a.x < width_ && a.y < height_)
      lines_in_view.push_back(i);
  }
  if (lines_in_view.size() > kMaxLinePaths) {
    const std::vector<LabelEntry>& all = set_.labels();
    std::stable_sort(lines_in_view.begin(), lines_in_view.end(), [&](uint32_t a, uint32_t b) {
      const bool sa = shown_lines.count(a) != 0, sb = shown_lines.count(b) != 0;
      if (sa != sb) return sa;
      return all[a].rank > all[b].rank;
    });
    lines_in_view.resize(kMaxLinePaths);
  }
  std::vector<LabelProbe> path_in;
  std::vector<uint32_t> path_base(set_.labels().size(), UINT32_MAX);
  for (uint32_t i : lines_in_view) {
    const auto [first, count] = path_probes_[i];
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
  const float pad = 100;  // labels may reach this far past the screen's edge
  auto on_screen = [&](float x, float y) {
    return x >= 0 && y >= 0 && x < float(width_) && y < float(height_);
  };

  std::vector<Layout> lays;
  std::vector<float> samples;  // x, y
  auto add_sample = [&](Layout& l, float x, float y, float expected) {
    samples.push_back(x), samples.push_back(y);
    l.expected.push_back(expected);
    ++l.sample_count;
  };
  // The legends and charts: no label covers one, and a place's label goes
  // beside its chart.
  std::vector<ScreenBox> obstacles;
  for (const SceneLayer* layer : below_)
    for (const glm::vec4& b : layer->overlay_boxes())
      obstacles.push_back({b.x, b.y, b.z, b.w});
  struct Disc {
    float x, y, r;
  };
  std::vector<Disc> discs;
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
    for (size_t c = 0; c < at.size(); ++c) {
      if (!at[c].front || radii[c] <= 0) continue;
      const float r = radii[c];
      discs.push_back({at[c].x, at[c].y, r});
      obstacles.push_back(
          {at[c].x - 0.8f * r, at[c].y - 0.8f * r, at[c].x + 0.8f * r, at[c].y + 0.8f * r});
    }
  }
  constexpr float kDiscCell = 64;
  std::unordered_map<int64_t, std::vector<uint32_t>> disc_cells;
  auto cell_of = [&](float x, float y) {
    return (int64_t(std::floor(y / kDiscCell)) << 32) ^
           int64_t(uint32_t(int32_t(std::floor(x / kDiscCell))));
  };
  for (uint32_t c = 0; c < discs.size(); ++c) {
    const Disc& d = discs[c];
    for (float y = std::floor((d.y - d.r) / kDiscCell); y <= std::floor((d.y + d.r) / kDiscCell);
         ++y)
      for (float x = std::floor((d.x - d.r) / kDiscCell); x <= std::floor((d.x + d.r) / kDiscCell);
           ++x)
        disc_cells[cell_of(x * kDiscCell, y * kDiscCell)].push_back(c);
  }
  // The radius of the largest chart covering pixel (x, y), 0 for none.
  auto chart_radius_at = [&](float x, float y) {
    float r = 0;
    auto it = disc_cells.find(cell_of(x, y));
    if (it == disc_cells.end()) return r;
    for (uint32_t c : it->second) {
      const Disc& d = discs[c];
      if (std::hypot(x - d.x, y - d.y) <= d.r + 1) r = std::max(r, d.r);
    }
    return r;
  };

  const glm::dmat4 unproject = glm::inverse(view.proj * view.view);
  // The unit sight line through pixel (x, y) from the top-left.
  auto ray = [&](float x, float y) {
    const double nx = 2.0 * x / width_ - 1, ny = 1 - 2.0 * y / height_;
    const glm::dvec4 p0 = unproject * glm::dvec4(nx, ny, -1, 1);
    const glm::dvec4 p1 = unproject * glm::dvec4(nx, ny, 1, 1);
    return glm::normalize(glm::dvec3(p1) / p1.w - glm::dvec3(p0) / p0.w);
  };
  std::vector<LabelEntry>& labels = set_.labels();
  for (uint32_t i = 0; i < labels.size(); ++i) {
    if (anchor_probe_[i] == UINT32_MAX) continue;
    const ProbeResult& a = probes[anchor_probe_[i]];
    if (!a.front || !on_screen(a.x, a.y)) continue;  // a label shows while its anchor does
    LabelEntry& e = labels[i];
    const ShapedLabel& s = set_.shaped(e);
    if (!s.ok) continue;
    const double sd = std::min(kMaxScale, 0.5 + 0.5 * d_ref / std::max(a.distance, 1e-3f));
    const bool area = e.record.placement == tileformat::LabelPlacement::kArea;
    const float size = static_cast<float>(settings_.size_px * (area ? 1.1 : 1.0) * sd);
    const float k = size / LabelSet::kAtlasPx;
    const float w = s.width * k, asc = s.ascent * k, desc = s.descent * k;
    const float baseline = (asc - desc) / 2;  // text centred on its line
    ++candidates_;
    const auto [first, count] = path_probes_[i];
    if (count >= 2 && path_base[i] == UINT32_MAX) continue;  // a line label deferred
    if (e.record.placement != tileformat::LabelPlacement::kLine || count < 2) {
      Layout l;
      l.label = i, l.key = uint64_t(i) << 4, l.scale = k, l.distance = a.distance;
      l.legible = sd >= kShowScale;
      // A point label goes right of its place, else left, above or below,
      // clear of the place's chart; an area label on its anchor.
      const float chart_r = area ? 0.f : chart_radius_at(a.x, a.y);
      const float gap = area ? 0.f : std::max(0.45f * size, chart_r + 3);
      const float h = asc + desc;
      const float x0 = area ? a.x - w / 2 : a.x + gap;
      for (const LabelGlyph& g : s.glyphs)
        l.pivots.push_back({x0 + g.x * k, a.y - g.y * k, 0.f});
      l.baseline = baseline;
      l.box = {x0 - 1, a.y + baseline - asc - 1, x0 + w + 1, a.y + baseline + desc + 1};
      l.boxes = {l.box};
      if (!area)
        l.shifts = {{0, 0},
                    {-(2 * gap + w), 0},
                    {-(gap + w / 2), -(gap + h / 2)},
                    {-(gap + w / 2), gap + h / 2}};
      l.sample_first = samples.size() / 2;
      // The anchor, and the middle row of the label in each of its places.
      // The label stands on the ground at its anchor: where a sample's sight
      // line meets terrain before the ground's tangent plane there, terrain
      // is in front of the label (a ridge crossing it); the tangent plane
      // keeps the globe's curvature and the view's perspective from counting.
      const glm::dvec3 eye = view.eye;
      const glm::dvec3 anchor_point = eye + ray(a.x, a.y) * double(a.distance);
      const glm::dvec2 key = anchor_key_[i];
      const glm::dvec3 up =
          glm::normalize(pass.world.key_to_world(key.x, key.y, 1000, view.origin) -
                         pass.world.key_to_world(key.x, key.y, 0, view.origin));
      const double plane = glm::dot(anchor_point - eye, up);
      add_sample(l, a.x, a.y, a.distance);
      for (const BoxShift& sh : l.shifts) {
        const float y = (l.box.y0 + l.box.y1) / 2 + sh.dy;
        for (float x : {l.box.x0, (l.box.x0 + l.box.x1) / 2, l.box.x1}) {
          const double down = glm::dot(ray(x + sh.dx, y), up);
          add_sample(l, x + sh.dx, y, down < -1e-6 ? float(plane / down) : -1.f);
        }
      }
      lays.push_back(std::move(l));
      continue;
    }
    // A line label: along the screen path of its line, from its middle.
    std::vector<PathPoint> path;
    for (uint32_t p = first; p < first + count; ++p) {
      const ProbeResult& q = path_at_screen[path_base[i] + (p - first)];
      const bool usable =
          q.front && q.x > -pad && q.y > -pad && q.x < width_ + pad && q.y < height_ + pad;
      if (!usable) {
        if (path.size() >= 2) break;  // keep the first usable stretch
        path.clear();
        continue;
      }
      const float s_len =
          path.empty() ? 0 : path.back().s + std::hypot(q.x - path.back().x, q.y - path.back().y);
      path.push_back({q.x, q.y, s_len, q.distance, p});
    }
    if (path.size() < 2 || path.back().s < w + 4) continue;
    // The middle's place on the path: the point nearest the anchor.
    float s_mid = 0, best = HUGE_VALF;
    for (size_t p = 1; p < path.size(); ++p) {
      const float dx = path[p].x - path[p - 1].x, dy = path[p].y - path[p - 1].y;
      const float len2 = std::max(dx * dx + dy * dy, 1e-9f);
      const float t =
          std::clamp(((a.x - path[p - 1].x) * dx + (a.y - path[p - 1].y) * dy) / len2, 0.f, 1.f);
      const float ex = path[p - 1].x + dx * t - a.x, ey = path[p - 1].y + dy * t - a.y;
      if (ex * ex + ey * ey < best)
        best = ex * ex + ey * ey, s_mid = path[p - 1].s + t * std::sqrt(len2);
    }
    const float spacing = std::max(3 * w, 250.f);
    const float total = path.back().s;
    // A glyph's sample: where its sight line meets the ground's tangent plane
    // at the path's nearest point (on a curved globe the ground falls away
    // from that plane, so a long segment never counts as terrain in front).
    const glm::dvec2 key = anchor_key_[i];
    const glm::dvec3 up = glm::normalize(pass.world.key_to_world(key.x, key.y, 1000, view.origin) -
                                         pass.world.key_to_world(key.x, key.y, 0, view.origin));
    auto expected_at = [&](float px, float py, float s_along) {
      size_t v = 1;
      while (v + 1 < path.size() && path[v].s < s_along)
        ++v;
      const PathPoint& near = s_along - path[v - 1].s < path[v].s - s_along ? path[v - 1] : path[v];
      const glm::dvec3 ground = view.eye + ray(near.x, near.y) * double(near.d);
      const double down = glm::dot(ray(px, py), up);
      return down < -1e-6 ? float(glm::dot(ground - view.eye, up) / down) : -1.f;
    };
    for (int rep = -kRepeatsEachSide; rep <= kRepeatsEachSide; ++rep) {
      const float centre = s_mid + float(rep) * spacing;
      if (centre - w / 2 < 0 || centre + w / 2 > total) continue;
      // Upright: the text runs left to right on screen.
      const PathAt p0 = path_at(path, centre - w / 2), p1 = path_at(path, centre + w / 2);
      // Glyphs along the path one way or the other: upright (every glyph
      // within 90 degrees of level) and turning at most kMaxTurnDeg between
      // neighbours, or not at all.
      auto lay = [&](bool flip, Layout& l) {
        l.pivots.clear(), l.boxes.clear(), l.expected.clear();
        l.sample_count = 0;
        l.sample_first = samples.size() / 2;
        l.box = {HUGE_VALF, HUGE_VALF, -HUGE_VALF, -HUGE_VALF};
        float last_angle = 0;
        bool have_angle = false;
        for (const LabelGlyph& g : s.glyphs) {
          const float along = (g.x + g.advance / 2) * k;
          const float at = flip ? centre + w / 2 - along : centre - w / 2 + along;
          PathAt q = path_at(path, at);
          if (flip) q.angle += std::numbers::pi_v<float>;
          q.angle = std::remainder(q.angle, 2 * std::numbers::pi_v<float>);
          const float turn = std::remainder(q.angle - last_angle, 2 * std::numbers::pi_v<float>);
          if (std::abs(q.angle) > std::numbers::pi_v<float> / 2 ||
              (have_angle && std::abs(turn) > kMaxTurnDeg * std::numbers::pi_v<float> / 180)) {
            samples.resize(l.sample_first * 2);
            return false;
          }
          last_angle = q.angle, have_angle = true;
          l.pivots.push_back({q.x, q.y, q.angle});
          const float r = std::max(asc + desc, g.advance * k) / 2;
          const ScreenBox b{q.x - r, q.y - r, q.x + r, q.y + r};
          l.boxes.push_back(b);
          l.box = {std::min(l.box.x0, b.x0), std::min(l.box.y0, b.y0), std::max(l.box.x1, b.x1),
                   std::max(l.box.y1, b.y1)};
          add_sample(l, q.x, q.y, expected_at(q.x, q.y, at));
        }
        return true;
      };
      Layout l;
      l.label = i, l.key = (uint64_t(i) << 4) | uint64_t(rep + kRepeatsEachSide);
      l.scale = k, l.distance = a.distance, l.legible = sd >= kShowScale, l.baseline = baseline;
      l.along_line = true;
      const bool flip = p1.x < p0.x;
      if (!lay(flip, l) && !lay(!flip, l)) continue;
      lays.push_back(std::move(l));
    }
  }

  // The terrain's distance at every sample: a label whose samples see
  // terrain nearer than the label is behind it.
  const std::vector<float> terrain =
      timed([&] { return renderer_.terrain_distances(samples, pass.g, view); });
  const std::unordered_set<uint64_t> drawn_before(last_placed_keys_.begin(),
                                                  last_placed_keys_.end());
  std::vector<LabelBid> bids(lays.size());
  for (size_t b = 0; b < lays.size(); ++b) {
    const Layout& l = lays[b];
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
    const Layout& l = lays[b];
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
