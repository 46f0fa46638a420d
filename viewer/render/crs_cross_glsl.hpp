// GLSL of the crossing between the terrain's CRS and a layer's, geodetic <->
// webmercator in closed form (camera/layer_tiling.hpp does the same in
// double on the CPU): offsets from an anchor near the eye, written without
// cancellation, so float stays exact for small offsets.
#pragma once

namespace globe::viewer::shaders {

inline constexpr const char* kCrsCrossGlsl = R"(
const float kMaxMercLat = 1.4844222297453324;  // 85.0511 degrees

// The layer CRS offset c (x east, y north) from the anchor of the terrain CRS
// offset d from the view origin; mode 1 geodetic -> webmercator (param: lat0
// in radians, R), 2 webmercator -> geodetic (param: y0 / R, R). Returns
// false where a latitude past webmercator's edge was clamped to it.
bool cross_offset(int mode, vec2 param, vec2 d, out vec2 c) {
  if (mode == 1) {
    float lat0 = param.x, R = param.y, dl = radians(d.y);
    float lat = clamp(lat0 + dl, -kMaxMercLat, kMaxMercLat);
    bool inside = lat == lat0 + dl;
    dl = lat - lat0;
    // atanh(sin lat) - atanh(sin lat0), without cancellation for small dl.
    float num = 2.0 * cos(lat0 + 0.5 * dl) * sin(0.5 * dl);
    c = vec2(R * radians(d.x), R * atanh(clamp(num / (1.0 - sin(lat) * sin(lat0)), -0.999999, 0.999999)));
    return inside;
  }
  float b = param.x, R = param.y, a = b + d.y / R;
  // atan(sinh a) - atan(sinh b), likewise.
  float num = 2.0 * cosh(0.5 * (a + b)) * sinh(0.5 * (a - b));
  c = vec2(degrees(d.x / R), degrees(atan(num, 1.0 + sinh(a) * sinh(b))));
  return true;
}
)";

}  // namespace globe::viewer::shaders
