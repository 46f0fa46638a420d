// The kinds of package (docs/tileformat.md §3.2) and one descriptor per kind:
// how its `format` value reads, what messages call it, which command makes it
// and which tool inspects it. Code that must tell the kinds apart (package
// openers, `info`, `validate`, `extract`, the GDAL driver's hints) reads this
// table instead of switching on the kind; adding a kind adds one row here
// (docs/architecture.md, "A new package kind"): its enumerator and its row
// below.
#pragma once

#include <optional>
#include <span>
#include <string>

namespace tileformat {

// `format` values of our own kinds (imagery uses png, jpg or webp).
inline constexpr const char* kMBlockFormat = "application/vnd.globe.mblock";
inline constexpr const char* kLineClustersFormat = "application/vnd.globe.lineclusters";
inline constexpr const char* kAnalysisFormat = "application/vnd.globe.analysis";
inline constexpr const char* kPointsFormat = "application/vnd.globe.points";
inline constexpr const char* kAreasFormat = "application/vnd.globe.areas";

// The kinds of package; the `format` key tells them apart.
enum class PackageKind { kTerrain, kImage, kLines, kAnalysis, kPoints, kAreas };

struct PackageKindDescriptor {
  PackageKind kind;
  const char* name;      // for messages: "terrain", "line-cluster", …
  const char* info_key;  // `info --json`'s "kind" and the object it adds: "terrain", "lines", …
  const char* maker;     // the command that makes it: "globe-tiler terrain"
  const char* tool;      // the tool whose info, validate and extract read it
  const char* extract;   // what `extract` writes of it, e.g. "its lines: globe-vectorize …"
  const char* format;    // its `format` value; nullptr: an image format (png, jpg, webp)
};

// One row per kind, in PackageKind order (Metadata.EveryKindHasOneDescriptor).
inline constexpr PackageKindDescriptor kPackageKinds[] = {
    {PackageKind::kTerrain, "terrain", "terrain", "globe-tiler terrain", "globe-tiler",
     "its heights: globe-tiler extract PACKAGE --zoom Z -o OUT.tif", kMBlockFormat},
    {PackageKind::kImage, "image", "image", "globe-tiler imagery", "globe-tiler",
     "a zoom as GeoTIFF: globe-tiler extract PACKAGE --zoom Z -o OUT.tif", nullptr},
    {PackageKind::kLines, "line-cluster", "lines", "globe-vectorize lines or bundle",
     "globe-vectorize", "its lines: globe-vectorize extract PACKAGE --zoom Z -o OUT.gpkg",
     kLineClustersFormat},
    {PackageKind::kAnalysis, "analysis", "analysis", "globe-tiler analyze", "globe-tiler",
     "a layer: globe-tiler extract PACKAGE --layer NAME --zoom Z -o OUT.tif", kAnalysisFormat},
    {PackageKind::kPoints, "point", "points", "globe-vectorize points", "globe-vectorize",
     "its places: globe-vectorize extract PACKAGE --zoom Z -o OUT.gpkg", kPointsFormat},
    {PackageKind::kAreas, "area", "areas", "globe-vectorize areas", "globe-vectorize",
     "its polygons: globe-vectorize extract PACKAGE --zoom Z -o OUT.gpkg", kAreasFormat},
};

// Every kind, in PackageKind order.
std::span<const PackageKindDescriptor> package_kinds();
const PackageKindDescriptor& describe(PackageKind kind);
// Whether a `format` value is this kind's.
bool is_format_of(const PackageKindDescriptor& kind, const std::string& format);

// The kind whose `format` value this is (terrain and lines by their media
// type, imagery by png/jpg/webp), or nullopt.
std::optional<PackageKind> package_kind_of_format(const std::string& format);
// describe(kind).name: "terrain", "image", "line-cluster", "analysis" or "point".
const char* package_kind_name(PackageKind kind);

}  // namespace tileformat
