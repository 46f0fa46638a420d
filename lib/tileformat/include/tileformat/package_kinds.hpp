// The kinds of package (docs/tileformat.md §3.2) and one descriptor per kind:
// how its `format` value reads, what messages call it, which command makes it
// and which tool inspects it. Code that must tell the kinds apart (package
// openers, `info`, `validate`, `extract`, the GDAL driver's hints) reads this
// table instead of switching on the kind; adding a kind adds one row here
// (docs/architecture.md, "A new package kind").
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

// The kinds of package; the `format` key tells them apart.
enum class PackageKind { kTerrain, kImage, kLines, kAnalysis, kPoints };

struct PackageKindDescriptor {
  PackageKind kind;
  const char* name;      // for messages: "terrain", "line-cluster", …
  const char* info_key;  // `info --json`'s "kind" and the object it adds: "terrain", "lines", …
  const char* maker;     // the command that makes it: "globe-tiler terrain"
  const char* tool;      // the tool whose info, validate and extract read it
  const char* extract;   // what `extract` writes of it, e.g. "its lines: globe-vectorize …"
  bool (*is_format)(const std::string& format);  // whether a `format` value is this kind's
};

// Every kind, in PackageKind order.
std::span<const PackageKindDescriptor> package_kinds();
const PackageKindDescriptor& describe(PackageKind kind);

// The kind whose `format` value this is (terrain and lines by their media
// type, imagery by png/jpg/webp), or nullopt.
std::optional<PackageKind> package_kind_of_format(const std::string& format);
// describe(kind).name: "terrain", "image", "line-cluster", "analysis" or "point".
const char* package_kind_name(PackageKind kind);

}  // namespace tileformat
