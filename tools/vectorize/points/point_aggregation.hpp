// Aggregating places for coarser zooms (docs/points.md "Aggregation"): the
// places of one zoom, and their merging into the places of the next coarser
// zoom, where places closer than a radius become one. Greedy in a fixed
// order (the heaviest place first, then the smallest id), so the result
// never depends on thread count or input order beyond the ids: the first
// place not yet taken takes every other untaken place within the radius of
// it; the merged place sits at their weighted centre and carries the sums of
// their values and counts and the smallest of their ids. Zooms are built
// from the next finer one, so zooming in splits a chart into the charts it
// was made of. On the global tilings distances wrap around the antimeridian.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace globe {

class PlaceSet {
 public:
  explicit PlaceSet(int fields) : fields_(fields) {}

  int fields() const { return fields_; }
  size_t size() const { return id_.size(); }
  void reserve(size_t n);
  // `sums`: `fields` values (a source place: its own).
  void add(double x, double y, uint64_t id, uint32_t count, std::span<const double> sums);

  double x(size_t i) const { return x_[i]; }
  double y(size_t i) const { return y_[i]; }
  uint64_t id(size_t i) const { return id_[i]; }
  uint32_t count(size_t i) const { return count_[i]; }
  std::span<const double> sums(size_t i) const {
    return {sums_.data() + i * size_t(fields_), size_t(fields_)};
  }
  // The weight of a place's position in a merged centre, and its rank in the
  // merge order: the sum of its values' magnitudes (its count when that is 0).
  double weight(size_t i) const;

 private:
  int fields_;
  std::vector<double> x_, y_, sums_;
  std::vector<uint64_t> id_;
  std::vector<uint32_t> count_;
};

// Where distances wrap: the CRS width once around the Earth (the global
// tilings; 0 for none) and the west edge x.
struct Wrap {
  double width = 0, west = 0;
};

// The places of `in` merged within `radius` (CRS units), in the merge order.
PlaceSet merge_places(const PlaceSet& in, double radius, Wrap wrap);

// The share of places that have another place within `radius`: what merging
// at that radius would touch (for choosing the finest zoom).
double crowded_share(const PlaceSet& in, double radius, Wrap wrap);

}  // namespace globe
