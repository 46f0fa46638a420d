// Places on disk, in the order the aggregation sweeps them (docs/points.md
// "Memory and speed"): north to south (descending y in the tiling's CRS),
// ties by id. A build never holds all places: the source places and each
// zoom's places go through an external sort (tiles/tile_sorter.hpp) keyed
// by y, and the sorted source is kept in a scratch file, read once per pass.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "kit/scratch_file.hpp"
#include "tiles/tile_sorter.hpp"

namespace globe {

// One place of a zoom: a source place (count 1, its own values) or a merged
// one (the count of source places it stands for, the sums of their values,
// the smallest of their ids).
struct Place {
  double x = 0, y = 0;  // tiling CRS
  uint64_t id = 0;
  uint32_t count = 1;
  std::vector<double> sums;
  // Its weight in a merged centre and its rank in the merge order: the sum of
  // its values' magnitudes (its count when that is 0).
  double weight() const;
};

// Places in sweep order, one at a time.
class PlaceSource {
 public:
  virtual ~PlaceSource() = default;
  // The next place into `place`; false at the end.
  virtual bool next(Place& place) = 0;
};

// Places added in any order come back in sweep order; memory stays within
// the budget (the rest spills to run files named `scratch_prefix`.N).
class PlaceSorter : public PlaceSource {
 public:
  PlaceSorter(std::string scratch_prefix, size_t memory_budget_bytes, int fields);
  void add(const Place& place);
  // Ends adding; next() then walks the places.
  void finish();
  bool next(Place& place) override;
  uint64_t size() const { return sorter_.records(); }

 private:
  TileSorter sorter_;
  int fields_;
  TileGroup group_;
  size_t at_ = 0;  // next record of group_
};

// Places appended in sweep order, read back as often as needed.
class PlaceFile : public PlaceSource {
 public:
  PlaceFile(std::string path, int fields);
  void append(const Place& place);
  // Ends writing, or starts reading again from the first place.
  void rewind();
  bool next(Place& place) override;
  uint64_t size() const { return size_; }

 private:
  ScratchFile file_;
  int fields_;
  uint64_t size_ = 0;
  std::vector<uint8_t> record_;
};

}  // namespace globe
