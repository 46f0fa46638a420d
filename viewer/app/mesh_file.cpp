// PLY mesh output (see mesh_file.hpp).
#include "app/mesh_file.hpp"

#include <array>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>

#include "errors.hpp"

namespace globe::viewer {

void write_mesh_ply(const std::string& path, const std::vector<float>& tris, const View& view,
                    const WorldFrame& frame, double exaggeration, double max_error_px) {
  // Weld on the exact float triple: shared vertices are bit-identical.
  std::map<std::array<float, 3>, uint32_t> index;
  std::vector<std::array<float, 3>> verts;
  std::vector<uint32_t> faces;
  faces.reserve(tris.size() / 3);
  for (size_t i = 0; i + 2 < tris.size(); i += 3) {
    const std::array<float, 3> v{tris[i], tris[i + 1], tris[i + 2]};
    auto [it, added] = index.emplace(v, static_cast<uint32_t>(verts.size()));
    if (added) verts.push_back(v);
    faces.push_back(it->second);
  }
  const double zs = frame.height_scale() * exaggeration;
  const glm::dvec2 eye_key = frame.world_to_key(view.eye.x, view.eye.y, view.origin);
  const glm::dvec2 eye_crs = frame.key_to_crs(eye_key.x, eye_key.y);
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary);
    if (!out) throw OutputError(path + ": cannot create " + tmp);
    char header[1024];
    std::snprintf(header, sizeof header,
                  "ply\nformat binary_little_endian 1.0\n"
                  "comment globe-view mesh: x y = tiling CRS, z = height in metres\n"
                  "comment globe crs %s\n"
                  "comment globe metres_per_crs %.17g %.17g\n"
                  "comment globe height_scale %.17g\n"
                  "comment globe eye_crs %.17g %.17g %.17g\n"
                  "comment globe pixels_per_radian %.17g\n"
                  "comment globe max_error_px %.17g\n"
                  "element vertex %zu\nproperty double x\nproperty double y\nproperty double z\n"
                  "element face %zu\nproperty list uchar uint vertex_indices\nend_header\n",
                  tileformat::scheme_name(frame.tiling().scheme), frame.metres_per_crs_x(),
                  frame.metres_per_crs_y(), zs, eye_crs.x, eye_crs.y, view.eye.z / zs,
                  view.pixels_per_radian, max_error_px, verts.size(), faces.size() / 3);
    out << header;
    for (const auto& v : verts) {
      const glm::dvec2 k = frame.world_to_key(v[0], v[1], view.origin);
      const glm::dvec2 c = frame.key_to_crs(k.x, k.y);
      const double xyz[3] = {c.x, c.y, double(v[2]) / zs};
      out.write(reinterpret_cast<const char*>(xyz), sizeof xyz);
    }
    for (size_t f = 0; f < faces.size(); f += 3) {
      const uint8_t n = 3;
      out.write(reinterpret_cast<const char*>(&n), 1);
      out.write(reinterpret_cast<const char*>(&faces[f]), 3 * sizeof(uint32_t));
    }
    if (!out.flush()) {
      std::remove(tmp.c_str());
      throw OutputError(path + ": write failed (disk full?)");
    }
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) throw OutputError(path + ": cannot rename into place: " + ec.message());
}

}  // namespace globe::viewer
