// The HTML globe-serve shows a person (docs/serve.md "Preview"): "/" lists the
// packages with their TileJSON and links to two views of all of them together
// (issue 55 part 3) and of each alone: MapLibre GL (the terrain as raster-DEM
// terrain and hillshade, the image packages in the order given, the vector
// packages with their generated styles over them) and CesiumJS (the terrain
// as quantized-mesh, the image packages draped in order, and the line and
// point packages over them as images the server draws: Cesium reads no
// vector tiles). The pages get the package list in their source; the views
// load the libraries from `lib_url` (globe-serve's own /lib, from the npm
// cache scripts/web-deps.sh fills, unless --lib-url points elsewhere).
#pragma once

#include <string>
#include <vector>

#include "serve/package_registry.hpp"

namespace globe::serve {

std::string index_page(const std::vector<PackageRegistry::Listed>& packages);
// `?pkg=NAME` shows that package alone; without it, all of `packages`.
std::string maplibre_page(const std::string& lib_url,
                          const std::vector<PackageRegistry::Listed>& packages);
std::string cesium_page(const std::string& lib_url,
                        const std::vector<PackageRegistry::Listed>& packages);

}  // namespace globe::serve
