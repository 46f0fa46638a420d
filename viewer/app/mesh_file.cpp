// PLY mesh output (see mesh_file.hpp).
#include "app/mesh_file.hpp"

#include <array>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>

#include "runtime/errors.hpp"

namespace globe::viewer {

void write_mesh_ply(const std::string& path, const std::vector<CapturedVertex>& tris,
                    const View& view, const WorldFrame& frame, double exaggeration,
                    double max_error_px) {
  // Weld on the key point and the height: shared vertices are the same sample.
  std::map<std::array<int64_t, 3>, uint32_t> index;
  std::vector<std::array<double, 3>> verts;
  std::vector<uint32_t> faces;
  faces.reserve(tris.size());
  for (const CapturedVertex& c : tris) {
    const int64_t kx = view.origin.x + c.key[0], ky = view.origin.y + c.key[1];
    int32_t hbits;
    std::memcpy(&hbits, &c.height_m, sizeof hbits);
    auto [it, added] =
        index.emplace(std::array<int64_t, 3>{kx, ky, hbits}, static_cast<uint32_t>(verts.size()));
    if (added) {
      if (frame.globe()) {
        const glm::dvec3 p = frame.key_to_ecef(double(kx), double(ky), c.height_m * exaggeration);
        verts.push_back({p.x, p.y, p.z});
      } else {
        const glm::dvec2 p = frame.key_to_crs(double(kx), double(ky));
        verts.push_back({p.x, p.y, double(c.height_m)});
      }
    }
    faces.push_back(it->second);
  }
  const double zs = frame.height_scale() * exaggeration;
  glm::dvec3 eye;
  if (frame.globe()) {
    const GlobeAnchor& a = frame.anchor(view.origin);
    eye = a.ecef + glm::transpose(a.enu) * view.eye;
  } else {
    const glm::dvec2 k = frame.world_to_key(view.eye.x, view.eye.y, view.origin);
    const glm::dvec2 c = frame.key_to_crs(k.x, k.y);
    eye = {c.x, c.y, view.eye.z / zs};
  }
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary);
    if (!out) throw OutputError(path + ": cannot create " + tmp);
    char header[1200];
    std::snprintf(header, sizeof header,
                  "ply\nformat binary_little_endian 1.0\n"
                  "comment globe-view mesh: %s\n"
                  "comment globe frame %s\n"
                  "comment globe crs %s\n"
                  "comment globe metres_per_crs %.17g %.17g\n"
                  "comment globe height_scale %.17g\n"
                  "comment globe eye %.17g %.17g %.17g\n"
                  "comment globe pixels_per_radian %.17g\n"
                  "comment globe max_error_px %.17g\n"
                  "element vertex %zu\nproperty double x\nproperty double y\nproperty double z\n"
                  "element face %zu\nproperty list uchar uint vertex_indices\nend_header\n",
                  frame.globe() ? "x y z = geocentric WGS84 (ECEF) metres"
                                : "x y = tiling CRS, z = height in metres",
                  frame.globe() ? "geocentric" : "flat",
                  tileformat::scheme_name(frame.tiling().scheme), frame.metres_per_crs_x(),
                  frame.metres_per_crs_y(), zs, eye.x, eye.y, eye.z, view.pixels_per_radian,
                  max_error_px, verts.size(), faces.size() / 3);
    out << header;
    for (const auto& v : verts)
      out.write(reinterpret_cast<const char*>(v.data()), 3 * sizeof(double));
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
