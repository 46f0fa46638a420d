// Where a label goes on screen (see label_layout.hpp).
#include "app/label_layout.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>

namespace globe::viewer {

namespace {

constexpr float kPi = std::numbers::pi_v<float>;

// Position and direction at arc length s of a screen path.
struct PathAt {
  float x, y, angle;
};
PathAt path_at(const std::vector<ScreenPathPoint>& p, float s) {
  size_t i = 1;
  while (i + 1 < p.size() && p[i].s < s)
    ++i;
  const ScreenPathPoint& a = p[i - 1];
  const ScreenPathPoint& b = p[i];
  const float len = std::max(b.s - a.s, 1e-6f);
  const float t = std::clamp((s - a.s) / len, 0.f, 1.f);
  return {a.x + (b.x - a.x) * t, a.y + (b.y - a.y) * t, std::atan2(b.y - a.y, b.x - a.x)};
}

// Where the sight line through (x, y) meets the plane through `ground` with
// normal `up`: its distance from the eye, -1 where it does not (looking up).
float plane_distance(const SightLines& sight, float x, float y, const glm::dvec3& ground,
                     const glm::dvec3& up) {
  const double down = glm::dot(sight.through(x, y), up);
  return down < -1e-6 ? float(glm::dot(ground - sight.eye(), up) / down) : -1.f;
}

}  // namespace

SightLines::SightLines(const View& view) : eye_(view.eye) {
  const glm::dmat4 unproject = glm::inverse(view.proj * view.view);
  auto direction = [&](double x, double y) {
    const double nx = 2.0 * x / view.width - 1, ny = 1 - 2.0 * y / view.height;
    const glm::dvec4 p0 = unproject * glm::dvec4(nx, ny, -1, 1);
    const glm::dvec4 p1 = unproject * glm::dvec4(nx, ny, 1, 1);
    return glm::dvec3(p1) / p1.w - glm::dvec3(p0) / p0.w;
  };
  d00_ = direction(0, 0);
  dx_ = direction(1, 0) - d00_;
  dy_ = direction(0, 1) - d00_;
}

LabelLayout lay_out_at_anchor(uint32_t label, const LabelText& t, const ProbeResult& a, bool area,
                              float chart_r, const glm::dvec3& up, const SightLines& sight,
                              LabelSamples& samples) {
  LabelLayout l;
  l.label = label, l.key = uint64_t(label) << 4, l.scale = t.k, l.distance = a.distance;
  const float w = t.width, h = t.ascent + t.descent;
  const float gap = area ? 0.f : std::max(0.45f * t.size, chart_r + 3);
  const float x0 = area ? a.x - w / 2 : a.x + gap;
  for (const LabelGlyph& g : t.shaped.glyphs)
    l.pivots.push_back({x0 + g.x * t.k, a.y - g.y * t.k, 0.f});
  l.baseline = (t.ascent - t.descent) / 2;  // text centred on the anchor's row
  l.box = {x0 - 1, a.y + l.baseline - t.ascent - 1, x0 + w + 1, a.y + l.baseline + t.descent + 1};
  l.boxes = {l.box};
  if (!area)
    l.shifts = {{0, 0},
                {-(2 * gap + w), 0},
                {-(gap + w / 2), -(gap + h / 2)},
                {-(gap + w / 2), gap + h / 2}};
  // The anchor, and the middle row of the label in each of its places. The
  // label stands on the ground at its anchor: where a pixel's sight line
  // meets terrain before the ground's tangent plane there, terrain is in
  // front of the label (a ridge crossing it); the tangent plane keeps the
  // globe's curvature and the view's perspective from counting.
  l.sample_first = samples.size();
  const glm::dvec3 ground = sight.eye() + sight.through(a.x, a.y) * double(a.distance);
  samples.add(l, a.x, a.y, a.distance);
  for (const BoxShift& sh : l.shifts) {
    const float y = (l.box.y0 + l.box.y1) / 2 + sh.dy;
    for (float x : {l.box.x0, (l.box.x0 + l.box.x1) / 2, l.box.x1})
      samples.add(l, x + sh.dx, y, plane_distance(sight, x + sh.dx, y, ground, up));
  }
  return l;
}

void lay_out_along_path(uint32_t label, const LabelText& t, const ProbeResult& a,
                        const std::vector<ScreenPathPoint>& path, int repeats, float max_turn_deg,
                        const std::function<glm::dvec3(uint32_t)>& up_of, const SightLines& sight,
                        LabelSamples& samples, std::vector<LabelLayout>& out) {
  const float w = t.width;
  if (path.size() < 2 || path.back().s < w + 4) return;
  // The middle's place on the path: the point nearest the anchor.
  float s_mid = 0, best = HUGE_VALF;
  for (size_t p = 1; p < path.size(); ++p) {
    const float dx = path[p].x - path[p - 1].x, dy = path[p].y - path[p - 1].y;
    const float len2 = std::max(dx * dx + dy * dy, 1e-9f);
    const float u =
        std::clamp(((a.x - path[p - 1].x) * dx + (a.y - path[p - 1].y) * dy) / len2, 0.f, 1.f);
    const float ex = path[p - 1].x + dx * u - a.x, ey = path[p - 1].y + dy * u - a.y;
    if (ex * ex + ey * ey < best)
      best = ex * ex + ey * ey, s_mid = path[p - 1].s + u * std::sqrt(len2);
  }
  // A glyph's pixel against the ground's tangent plane at the path's nearest
  // point (on a curved globe the ground falls away from that plane, so a
  // long segment never counts as terrain in front).
  auto expected_at = [&](float px, float py, float s_along) {
    size_t v = 1;
    while (v + 1 < path.size() && path[v].s < s_along)
      ++v;
    const ScreenPathPoint& near =
        s_along - path[v - 1].s < path[v].s - s_along ? path[v - 1] : path[v];
    const glm::dvec3 ground = sight.eye() + sight.through(near.x, near.y) * double(near.d);
    return plane_distance(sight, px, py, ground, up_of(near.point));
  };
  const float spacing = std::max(3 * w, 250.f), total = path.back().s;
  const float max_turn = max_turn_deg * kPi / 180;
  for (int rep = -repeats; rep <= repeats; ++rep) {
    const float centre = s_mid + float(rep) * spacing;
    if (centre - w / 2 < 0 || centre + w / 2 > total) continue;
    // Glyphs along the path one way or the other: upright (every glyph
    // within 90 degrees of level), turning at most max_turn between
    // neighbours, or not at all.
    LabelLayout l;
    l.label = label, l.key = (uint64_t(label) << 4) | uint64_t(rep + repeats);
    l.scale = t.k, l.distance = a.distance, l.along_line = true;
    l.baseline = (t.ascent - t.descent) / 2;
    auto lay = [&](bool flip) {
      l.pivots.clear(), l.boxes.clear(), l.expected.clear();
      l.sample_count = 0;
      l.sample_first = samples.size();
      l.box = {HUGE_VALF, HUGE_VALF, -HUGE_VALF, -HUGE_VALF};
      float last_angle = 0;
      for (const LabelGlyph& g : t.shaped.glyphs) {
        const float along = (g.x + g.advance / 2) * t.k;
        const float at = flip ? centre + w / 2 - along : centre - w / 2 + along;
        PathAt q = path_at(path, at);
        q.angle = std::remainder(q.angle + (flip ? kPi : 0.f), 2 * kPi);
        const float turn = std::remainder(q.angle - last_angle, 2 * kPi);
        if (std::abs(q.angle) > kPi / 2 || (!l.pivots.empty() && std::abs(turn) > max_turn)) {
          samples.xy.resize(l.sample_first * 2);
          return false;
        }
        last_angle = q.angle;
        l.pivots.push_back({q.x, q.y, q.angle});
        const float r = std::max(t.ascent + t.descent, g.advance * t.k) / 2;
        const ScreenBox b{q.x - r, q.y - r, q.x + r, q.y + r};
        l.boxes.push_back(b);
        l.box = {std::min(l.box.x0, b.x0), std::min(l.box.y0, b.y0), std::max(l.box.x1, b.x1),
                 std::max(l.box.y1, b.y1)};
        samples.add(l, q.x, q.y, expected_at(q.x, q.y, at));
      }
      return true;
    };
    // The text runs left to right on screen where it can.
    const bool flip = path_at(path, centre + w / 2).x < path_at(path, centre - w / 2).x;
    if (lay(flip) || lay(!flip)) out.push_back(std::move(l));
  }
}

}  // namespace globe::viewer
