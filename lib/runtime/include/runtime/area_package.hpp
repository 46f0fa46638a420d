// Opening an existing area package for inspection, export and serving: the
// reader plus the metadata, checked once.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "runtime/line_style.hpp"
#include "runtime/package_open.hpp"
#include "tileformat/metadata.hpp"
#include "tileformat/package.hpp"

namespace globe {

struct AreaPackage {
  // The package file or, in globe-view, a remote source (package_open.hpp).
  std::unique_ptr<tileformat::TileReader> reader;
  // The file itself, for its other tables and whole-package reads; throws
  // InputError for a remote source.
  tileformat::PackageReader& file() const { return package_file(*reader); }
  tileformat::AreaMetadata meta;        // every key, as lib/tileformat reads it
  std::vector<NamedLineStyle> classes;  // style classes by class id (metadata globe:classes)
};

// Throws InputError naming the file if it is missing, not a package, or not
// an area package.
AreaPackage open_area_package(const std::string& path);

// How one class of an area package is drawn, the same in the viewer, the
// MapLibre style and the drawn tiles (docs/areas.md "Looks").
struct AreaLook {
  std::string fill;         // "#rrggbb"
  double opacity = 1;       // the class's own, times the drawing's fill opacity
  std::string outline;      // "#rrggbb"
  double outline_px = 0.5;  // 0: none
  bool visible = true;
};

// Per class id: a choropleth's no-data class (0), then its classes; else
// the style classes (colour and opacity; their casing is the outline, else a
// thin #444444). `fill_opacity` multiplies every class's opacity.
std::vector<AreaLook> area_looks(const AreaPackage& package, double fill_opacity);

}  // namespace globe
