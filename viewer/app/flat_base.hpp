// The ground under layers viewed without a terrain (docs/viewer.md "Without
// terrain"): a terrain package of zero heights in the first layer's tiling,
// written to a scratch file for the session (removed when it ends), so that
// the terrain pass, its G-buffer and every per-pixel layer work unchanged.
// On the globe it is the bare WGS84 ellipsoid (the whole Earth at coarse
// zooms, the layer's area down to blocks whose chords sag < 1 m); on the map
// frame a flat base.
#pragma once

#include <string>

#include "app/package_set.hpp"

namespace globe::viewer {

class FlatBase {
 public:
  // Writes the base for set's layers (lines, points or imagery; the first
  // found gives the tiling and bounds). Throws InputError if none is given
  // and OutputError if the scratch file cannot be written.
  explicit FlatBase(const PackageSet& set);
  ~FlatBase();
  FlatBase(const FlatBase&) = delete;
  FlatBase& operator=(const FlatBase&) = delete;

  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

}  // namespace globe::viewer
