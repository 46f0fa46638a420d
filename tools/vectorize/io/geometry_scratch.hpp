// Pass 1's output (lines_builder.hpp): the projected features, appended to a
// scratch file next to the output and read back in order by the cut pass.
// One scratch record per feature (kit/scratch_file.hpp) in the one byte codec:
// id (u64), class (u32), zooms (u32), part and point counts (u32), each part's vertex
// count (u32) and coordinates (f64 x, y), then the points.
#pragma once

#include <string>
#include <vector>

#include "kit/scratch_file.hpp"
#include "tiles/tile_cutter.hpp"

namespace globe {

class GeometryScratch {
 public:
  explicit GeometryScratch(std::string path) : file_(std::move(path)) {}
  void write(const ProjectedFeature& f);
  // Ends writing; read() then returns the features from the first.
  void rewind() { file_.rewind(); }
  // The next feature; false at the end.
  bool read(ProjectedFeature& f);

 private:
  ScratchFile file_;
  std::vector<uint8_t> buffer_;
};

}  // namespace globe
