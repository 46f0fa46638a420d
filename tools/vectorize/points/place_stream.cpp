// Places on disk (see place_stream.hpp).
#include "points/place_stream.hpp"

#include <bit>
#include <cmath>

#include "tileformat/byte_io.hpp"

namespace globe {
namespace {

// A key whose unsigned order is descending y (-0 and 0 alike).
uint64_t descending_y_key(double y) {
  const uint64_t bits = std::bit_cast<uint64_t>(y == 0 ? 0.0 : y);
  const uint64_t ascending = (bits >> 63) ? ~bits : bits | (uint64_t{1} << 63);
  return ~ascending;
}

// x, y, count and the sums; the id travels beside them.
void encode(const Place& p, tileformat::ByteWriter& w) {
  w.f64(p.x);
  w.f64(p.y);
  w.u32(p.count);
  for (double v : p.sums)
    w.f64(v);
}

void decode(tileformat::ByteReader& r, int fields, Place& p) {
  p.x = r.f64();
  p.y = r.f64();
  p.count = r.u32();
  p.sums.resize(size_t(fields));
  for (double& v : p.sums)
    v = r.f64();
}

}  // namespace

double Place::weight() const {
  double w = 0;
  for (double v : sums)
    w += std::abs(v);
  return w > 0 ? w : double(count);
}

PlaceSorter::PlaceSorter(std::string scratch_prefix, size_t memory_budget_bytes, int fields)
    : sorter_(std::move(scratch_prefix), memory_budget_bytes), fields_(fields) {}

void PlaceSorter::add(const Place& place) {
  tileformat::ByteWriter w;
  encode(place, w);
  sorter_.add(descending_y_key(place.y), place.id, 0, w.take());
}

void PlaceSorter::finish() {
  sorter_.finish();
}

bool PlaceSorter::next(Place& place) {
  while (at_ == group_.records.size()) {
    if (!sorter_.next_group(group_)) return false;
    at_ = 0;
  }
  const TileRecord& rec = group_.records[at_++];
  tileformat::ByteReader r(group_.payload(rec), "sorted place", "scratch");
  decode(r, fields_, place);
  place.id = rec.seq;
  return true;
}

PlaceFile::PlaceFile(std::string path, int fields) : file_(std::move(path)), fields_(fields) {}

void PlaceFile::append(const Place& place) {
  tileformat::ByteWriter w;
  w.u64(place.id);
  encode(place, w);
  file_.append(w.take());
  ++size_;
}

void PlaceFile::rewind() {
  file_.rewind();
}

bool PlaceFile::next(Place& place) {
  if (!file_.next(record_)) return false;
  tileformat::ByteReader r(record_, "scratch place", "scratch");  // short names: no allocation
  place.id = r.u64();
  decode(r, fields_, place);
  return true;
}

}  // namespace globe
