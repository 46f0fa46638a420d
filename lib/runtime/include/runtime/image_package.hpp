// Opening an existing image package for inspection (tileformat §8): the
// reader plus the metadata every inspection command needs, checked once.
// MBTiles from other tools (no globe: keys) are read as webmercator, with the
// tile size and colour taken from their first tile.
#pragma once

#include "tileformat/metadata.hpp"

#include <memory>
#include <string>

#include "runtime/package_open.hpp"
#include "tileformat/image_tile.hpp"
#include "tileformat/package.hpp"
#include "tileformat/tiling.hpp"

namespace globe {

struct ImagePackage {
  // The package file or, in globe-view, a remote source (package_open.hpp).
  std::unique_ptr<tileformat::TileReader> reader;
  // The file itself, for its other tables and whole-package reads; throws
  // InputError for a remote source.
  tileformat::PackageReader& file() const { return package_file(*reader); }
  tileformat::ImageMetadata meta;  // every key, as lib/tileformat reads it
  tileformat::Tiling tiling;       // the fields below repeat meta for brevity
  tileformat::ImageFormat format = tileformat::ImageFormat::kPng;
  int tile_size = 256, colour = 3, min_zoom = 0, max_zoom = 0;
};

// Throws InputError naming the file if it is missing, not a package, or not
// an image package.
ImagePackage open_image_package(const std::string& path);

}  // namespace globe
