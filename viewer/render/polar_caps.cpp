// Polar caps of the globe (see polar_caps.hpp).
#include "render/polar_caps.hpp"

#include <cmath>
#include <numbers>

#include <glm/gtc/type_ptr.hpp>
#include <glm/vec4.hpp>

#include "camera/ellipsoid.hpp"

namespace globe::viewer {

namespace {

constexpr int kSegments = 256;

// Vertices come from a storage buffer by gl_VertexID: three per triangle.
constexpr const char* kCapVertex = R"(#version 450 core
layout(std430, binding = 0) readonly buffer Vertices { vec4 verts[]; };
uniform mat4 u_view_proj;
void main() {
  gl_Position = u_view_proj * vec4(verts[gl_VertexID].xyz, 1.0);
}
)";

constexpr const char* kCapFragment = R"(#version 450 core
uniform vec3 u_colour;
layout(location = 0) out vec4 o_color;
layout(location = 1) out vec4 o_position;  // w = 0: not terrain
layout(location = 2) out vec4 o_normal;
layout(location = 3) out vec4 o_ground;
layout(location = 4) out vec2 o_ground_dy;
void main() {
  o_color = vec4(u_colour, 1.0);
  o_position = vec4(0.0);
  o_normal = vec4(0.0);
  o_ground = vec4(0.0);
  o_ground_dy = vec2(0.0);
}
)";

}  // namespace

PolarCaps::PolarCaps(const WorldFrame& frame, const tileformat::Bounds& ll, double finest_deg,
                     double low_m) {
  if (!frame.globe()) return;
  const bool merc = frame.tiling().scheme == tileformat::Scheme::kWebMercator;
  const double limit = merc ? wgs84::kMercatorMaxLat : 90.0;
  // A cap where the data reaches the tiling's limit (within two samples).
  const double reach = 2 * finest_deg;
  const double edge = merc ? limit : limit - finest_deg;
  const double height = merc ? 0.0 : low_m - 100;
  if (ll.max_y >= limit - reach) caps_.push_back({edge, height});
  if (ll.min_y <= -limit + reach) caps_.push_back({-edge, height});
  if (caps_.empty()) return;
  program_ = GlProgram("polar caps", kCapVertex, kCapFragment);
  gl::CreateBuffers(1, &buffer_);
  gl::CreateVertexArrays(1, &vao_);
}

PolarCaps::~PolarCaps() {
  if (buffer_) gl::DeleteBuffers(1, &buffer_);
  if (vao_) gl::DeleteVertexArrays(1, &vao_);
}

void PolarCaps::draw(const GBuffer& g, const View& view, const WorldFrame& frame,
                     glm::vec3 colour) {
  if (caps_.empty()) return;
  const GlobeAnchor& a = frame.anchor(view.origin);
  constexpr double d = std::numbers::pi / 180;
  auto world = [&](double lat_deg, double lon_rad, double h) {
    return glm::vec4(glm::vec3(a.enu * (wgs84::to_ecef(lat_deg * d, lon_rad, h) - a.ecef)), 1.0f);
  };
  std::vector<glm::vec4> verts;
  verts.reserve(caps_.size() * kSegments * 3);
  for (const Cap& c : caps_) {
    const glm::vec4 pole = world(c.edge_lat_deg > 0 ? 90 : -90, 0, c.height_m);
    for (int i = 0; i < kSegments; ++i) {
      const double l0 = 2 * std::numbers::pi * i / kSegments;
      const double l1 = 2 * std::numbers::pi * (i + 1) / kSegments;
      verts.push_back(pole);
      verts.push_back(world(c.edge_lat_deg, l0, c.height_m));
      verts.push_back(world(c.edge_lat_deg, l1, c.height_m));
    }
  }
  gl::NamedBufferData(buffer_, verts.size() * sizeof(glm::vec4), verts.data(), GL_STREAM_DRAW);
  gl::BindFramebuffer(GL_FRAMEBUFFER, g.fbo);
  gl::Viewport(0, 0, g.width, g.height);
  gl::Enable(GL_DEPTH_TEST);
  gl::DepthFunc(GL_LESS);
  gl::UseProgram(program_.id());
  gl::UniformMatrix4fv(program_.uniform("u_view_proj"), 1, GL_FALSE,
                       glm::value_ptr(view.view_proj));
  gl::Uniform3f(program_.uniform("u_colour"), colour.r, colour.g, colour.b);
  gl::BindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, buffer_);
  gl::BindVertexArray(vao_);
  gl::DrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(verts.size()));
  gl::BindVertexArray(0);
  gl::BindFramebuffer(GL_FRAMEBUFFER, 0);
  gl::check("drawing the polar caps");
}

}  // namespace globe::viewer
