// The package kinds' descriptors (see package_kinds.hpp).
#include "tileformat/package_kinds.hpp"

#include "tileformat/image_tile.hpp"

namespace tileformat {
namespace {

bool is_terrain(const std::string& f) {
  return f == kMBlockFormat;
}
bool is_image(const std::string& f) {
  return parse_image_format(f).has_value();
}
bool is_lines(const std::string& f) {
  return f == kLineClustersFormat;
}
bool is_analysis(const std::string& f) {
  return f == kAnalysisFormat;
}
bool is_points(const std::string& f) {
  return f == kPointsFormat;
}

// One row per kind, in PackageKind order (checked by describe()'s test).
constexpr PackageKindDescriptor kKinds[] = {
    {PackageKind::kTerrain, "terrain", "terrain", "globe-tiler terrain", "globe-tiler",
     "its heights: globe-tiler extract PACKAGE --zoom Z -o OUT.tif", is_terrain},
    {PackageKind::kImage, "image", "image", "globe-tiler imagery", "globe-tiler",
     "a zoom as GeoTIFF: globe-tiler extract PACKAGE --zoom Z -o OUT.tif", is_image},
    {PackageKind::kLines, "line-cluster", "lines", "globe-vectorize lines or bundle",
     "globe-vectorize", "its lines: globe-vectorize extract PACKAGE --zoom Z -o OUT.gpkg",
     is_lines},
    {PackageKind::kAnalysis, "analysis", "analysis", "globe-tiler analyze", "globe-tiler",
     "a layer: globe-tiler extract PACKAGE --layer NAME --zoom Z -o OUT.tif", is_analysis},
    {PackageKind::kPoints, "point", "points", "globe-vectorize points", "globe-vectorize",
     "its places: globe-vectorize extract PACKAGE --zoom Z -o OUT.gpkg", is_points},
};

}  // namespace

std::span<const PackageKindDescriptor> package_kinds() {
  return kKinds;
}

const PackageKindDescriptor& describe(PackageKind kind) {
  return kKinds[static_cast<size_t>(kind)];
}

std::optional<PackageKind> package_kind_of_format(const std::string& format) {
  for (const PackageKindDescriptor& d : kKinds)
    if (d.is_format(format)) return d.kind;
  return std::nullopt;
}

const char* package_kind_name(PackageKind kind) {
  return describe(kind).name;
}

}  // namespace tileformat
