// A camera pose in geographic terms (what --camera takes) and the view it
// gives in the world frame: eye, view/projection matrices, frustum planes and
// the pixels-per-radian factor the LOD selection needs.
#pragma once

#include <array>
#include <string>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "camera/world_frame.hpp"

namespace globe::viewer {

struct CameraPose {
  double lon = 0, lat = 0;  // degrees
  double height_m = 1000;   // eye height above the ellipsoid / sea level
  double heading_deg = 0;   // 0 = north, 90 = east
  double pitch_deg = 0;     // 0 = straight down, 90 = horizontal
  double fov_y_deg = 45;

  // "lon,lat,height_m,heading_deg,pitch_deg"; throws std::invalid_argument.
  static CameraPose parse(const std::string& text);
  std::string str() const;
};

struct View {
  KeyPoint origin;  // world frame origin (key units), near the eye
  glm::dvec3 eye;   // world metres
  glm::dmat4 view, proj;
  glm::mat4 view_proj;               // float, for the GPU
  std::array<glm::dvec4, 6> planes;  // inside: dot(plane, (p, 1)) >= 0
  int width = 0, height = 0;
  double pixels_per_radian = 0;  // height / (2 tan(fov_y / 2))
  double near_m = 1, far_m = 1e7;
};

// z_top_world: highest terrain point (world z), used for near/far planes.
View make_view(const CameraPose& pose, WorldFrame& frame, int width, int height, double z_top_world,
               double z_bottom_world);

// A pose looking straight down at the centre of `crs_bounds` from a height at
// which the whole box fits the view.
CameraPose fit_pose(const tileformat::Bounds& crs_bounds, WorldFrame& frame, int width, int height,
                    double z_top_m);

}  // namespace globe::viewer
