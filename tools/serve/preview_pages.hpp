// The HTML globe-serve shows a person (docs/serve.md "Preview"): "/" lists the
// packages with their TileJSON, and a MapLibre GL and a CesiumJS view of each;
// the views load the libraries from `lib_url` (globe-serve's own /lib, from
// the npm cache scripts/web-deps.sh fills, unless --lib-url points elsewhere).
#pragma once

#include <string>
#include <vector>

#include "serve/package_registry.hpp"

namespace globe::serve {

std::string index_page(const std::vector<PackageRegistry::Listed>& packages);
std::string maplibre_page(const std::string& lib_url);
std::string cesium_page(const std::string& lib_url);

}  // namespace globe::serve
