// Where one label goes on screen this frame (docs/labels.md, steps 3 and 4):
// its glyphs' pivots, the boxes it covers in each place it may take, and the
// pixels at which the terrain will be tested, each with the distance the
// ground would have there if nothing stood in front of the label. A place's
// label sits beside it, an area's on its anchor, a line's along the screen
// path of its line. Pure CPU: the label layer feeds it the frame's
// projections and reads the terrain's distances at the pixels afterwards.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "app/label_placement.hpp"
#include "camera/camera.hpp"
#include "data/label_set.hpp"
#include "render/label_renderer.hpp"

namespace globe::viewer {

struct LabelLayout {
  uint32_t label = 0;   // index into the label set
  uint64_t key = 0;     // the placer's key: the label, and a line label's copy
  float scale = 1;      // screen px per atlas texel
  float distance = 0;   // of its anchor from the eye
  bool legible = true;  // at or above the legibility cutoff
  bool along_line = false;
  std::vector<std::array<float, 3>> pivots;     // per glyph: x, y, angle (radians)
  float baseline = 0;                           // of the glyphs, px below their pivot
  ScreenBox box;                                // all of it, at the first place
  std::vector<ScreenBox> boxes;                 // what it covers, at the first place
  std::vector<BoxShift> shifts = {BoxShift{}};  // the places it may take
  size_t sample_first = 0, sample_count = 0;    // its pixels in LabelSamples
  std::vector<float> expected;                  // per pixel: the ground's distance there
};

// The unit sight line through a pixel (from the top-left) of a view: the
// unprojected far point minus the near point is linear in the pixel (both
// planes have one w), so three of them give every other.
class SightLines {
 public:
  explicit SightLines(const View& view);
  glm::dvec3 through(float x, float y) const {
    return glm::normalize(d00_ + double(x) * dx_ + double(y) * dy_);
  }
  const glm::dvec3& eye() const { return eye_; }

 private:
  glm::dvec3 d00_, dx_, dy_;  // the direction at pixel (0, 0) and per pixel right and down
  glm::dvec3 eye_;
};

// The pixels a frame tests against the terrain, for all its labels.
struct LabelSamples {
  std::vector<float> xy;  // x, y per pixel
  void add(LabelLayout& l, float x, float y, float expected) {
    xy.push_back(x), xy.push_back(y);
    l.expected.push_back(expected);
    ++l.sample_count;
  }
  size_t size() const { return xy.size() / 2; }
};

// A label's text at its size on screen.
struct LabelText {
  const ShapedLabel& shaped;
  float k = 1;  // screen px per atlas px
  float size = 0, width = 0, ascent = 0, descent = 0;
};

// A place's label right of it, else left, above or below, clear of its
// chart (radius chart_r, 0 for none); an area's label centred on its
// anchor. Samples: the anchor, and three pixels of the label's middle row in
// each place, tested against the ground's tangent plane at the anchor
// (`up`: the ground's up there).
LabelLayout lay_out_at_anchor(uint32_t label, const LabelText& t, const ProbeResult& anchor,
                              bool area, float chart_r, const glm::dvec3& up,
                              const SightLines& sight, LabelSamples& samples);

// A point of a line's path on screen.
struct ScreenPathPoint {
  float x = 0, y = 0;  // px from the top-left
  float s = 0;         // arc length from the path's start, px
  float d = 0;         // distance from the eye
  uint32_t point = 0;  // the path point it is (for up_of)
};

// A line label's copies along the screen path from the point nearest its
// anchor, every max(3 x its width, 250 px), up to `repeats` each side: each
// glyph at its advance along the path, turned to it, upright, turning at
// most max_turn_deg from its neighbour (else that copy is not placed).
// Samples: every glyph, against the ground's tangent plane at the path's
// nearest point (up_of(point): the ground's up there).
void lay_out_along_path(uint32_t label, const LabelText& t, const ProbeResult& anchor,
                        const std::vector<ScreenPathPoint>& path, int repeats, float max_turn_deg,
                        const std::function<glm::dvec3(uint32_t)>& up_of, const SightLines& sight,
                        LabelSamples& samples, std::vector<LabelLayout>& out);

}  // namespace globe::viewer
