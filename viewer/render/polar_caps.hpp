// Polar caps of the globe (docs/viewer.md "Globe"): where a package cannot
// reach a pole — webmercator stops at +-85.0511 degrees, and a geodetic
// package whose pixel-is-area data ends just short of +-90 has no pole row —
// a plain-coloured cap closes the hole instead of showing the sky through it.
// A cap is a fan of 256 segments at its edge latitude, drawn into the
// G-buffer after the terrain with depth test; its position marks it as "not
// terrain" for the deferred passes. Geodetic caps lie below any terrain
// (the package's lowest height less 100 m), so real pole data hides them.
#pragma once

#include <vector>

#include <glm/vec3.hpp>

#include "camera/camera.hpp"
#include "camera/world_frame.hpp"
#include "platform/gl.hpp"
#include "render/gl_program.hpp"
#include "render/terrain_renderer.hpp"

namespace globe::viewer {

class PolarCaps {
 public:
  // lonlat: the package's data bounds (degrees); finest_deg: its finest
  // sample spacing in degrees of latitude; low_m: its lowest height.
  PolarCaps(const WorldFrame& frame, const tileformat::Bounds& lonlat, double finest_deg,
            double low_m);
  ~PolarCaps();
  PolarCaps(const PolarCaps&) = delete;
  PolarCaps& operator=(const PolarCaps&) = delete;

  size_t count() const { return caps_.size(); }
  void draw(const GBuffer& g, const View& view, const WorldFrame& frame, glm::vec3 colour);

 private:
  struct Cap {
    double edge_lat_deg, height_m;  // signed edge latitude; the pole is its sign's
  };
  std::vector<Cap> caps_;
  GlProgram program_;
  GLuint buffer_ = 0, vao_ = 0;
};

}  // namespace globe::viewer
