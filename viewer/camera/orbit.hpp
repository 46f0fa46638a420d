// The window's camera: an orbit around a target point on the terrain
// (heading and pitch at the target, a distance), turned into a CameraPose.
// On the flat frame the target moves in key units with the frame's metric
// scales; on the globe it moves over the ellipsoid (east/north metres at the
// target), the eye stands at `distance` along the target's tilted normal, and
// the pose's heading and pitch are re-expressed at the eye, so the view
// orbits the globe from space and tilts near the ground alike.
#pragma once

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "camera/camera.hpp"
#include "camera/world_frame.hpp"

namespace globe::viewer {

class Orbit {
 public:
  Orbit() = default;
  // The orbit that gives `pose`, around the point it looks at on the level
  // `ground_m` (the ray's hit; looking above the horizon: its tangent point).
  static Orbit from_pose(const CameraPose& pose, WorldFrame& frame, double ground_m);
  CameraPose pose(WorldFrame& frame, double fov_y_deg) const;

  // Drags: heading/pitch by degrees; pan by screen pixels (px_per_rad: the
  // view's pixels per radian); zoom by a distance factor, moving the target
  // the same fraction towards `towards` (a world point under the cursor,
  // relative to `view`'s origin) when given.
  void turn(double d_heading_deg, double d_pitch_deg);
  void pan(double dx_px, double dy_px, double px_per_rad, WorldFrame& frame);
  void zoom(double factor, WorldFrame& frame, const View* view = nullptr,
            const glm::dvec3* towards = nullptr);

  double distance_m() const { return distance_m_; }
  double heading_deg() const { return heading_deg_; }
  double pitch_deg() const { return pitch_deg_; }

 private:
  // Flat: the target in key units. Globe: latitude/longitude in radians.
  glm::dvec2 target_{0, 0};
  double target_h_m_ = 0, distance_m_ = 1000, heading_deg_ = 0, pitch_deg_ = 0;
};

}  // namespace globe::viewer
