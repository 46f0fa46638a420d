// Place aggregation (see point_aggregation.hpp).
#include "points/point_aggregation.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <unordered_map>

namespace globe {

void PlaceSet::reserve(size_t n) {
  x_.reserve(n);
  y_.reserve(n);
  id_.reserve(n);
  count_.reserve(n);
  sums_.reserve(n * size_t(fields_));
}

void PlaceSet::add(double x, double y, uint64_t id, uint32_t count, std::span<const double> sums) {
  x_.push_back(x);
  y_.push_back(y);
  id_.push_back(id);
  count_.push_back(count);
  sums_.insert(sums_.end(), sums.begin(), sums.end());
}

double PlaceSet::weight(size_t i) const {
  double w = 0;
  for (double v : sums(i))
    w += std::abs(v);
  return w > 0 ? w : double(count(i));
}

namespace {

// Places bucketed into square cells of at least the radius (columns wrap on
// the global tilings), so a place's neighbours within the radius lie in the
// 3 x 3 cells around its own.
class CellIndex {
 public:
  CellIndex(const PlaceSet& places, double radius, Wrap wrap) : wrap_(wrap) {
    size_x_ = size_y_ = radius;
    if (wrap.width > 0) {
      columns_ = std::max<int64_t>(1, static_cast<int64_t>(std::floor(wrap.width / radius)));
      size_x_ = wrap.width / double(columns_);
    }
    order_.resize(places.size());
    std::iota(order_.begin(), order_.end(), uint32_t{0});
    std::vector<uint64_t> keys(places.size());
    for (size_t i = 0; i < places.size(); ++i)
      keys[i] = key(column(places.x(i)), row(places.y(i)));
    std::sort(order_.begin(), order_.end(), [&](uint32_t a, uint32_t b) {
      return keys[a] != keys[b] ? keys[a] < keys[b] : a < b;
    });
    for (size_t k = 0; k < order_.size();) {
      size_t end = k;
      while (end < order_.size() && keys[order_[end]] == keys[order_[k]])
        ++end;
      cells_.emplace(keys[order_[k]], std::pair(uint32_t(k), uint32_t(end)));
      k = end;
    }
  }

  // Calls fn(j) for every place in the cells around (x, y).
  template <typename Fn>
  void near(double x, double y, Fn fn) const {
    const int64_t cx = column(x), cy = row(y);
    int64_t seen[3] = {INT64_MIN, INT64_MIN, INT64_MIN};
    for (int dx = -1; dx <= 1; ++dx) {
      int64_t c = cx + dx;
      if (columns_ > 0) c = ((c % columns_) + columns_) % columns_;
      if (c == seen[0] || c == seen[1]) continue;  // few columns: each once
      seen[dx + 1] = c;
      for (int64_t r = cy - 1; r <= cy + 1; ++r) {
        auto it = cells_.find(key(c, r));
        if (it == cells_.end()) continue;
        for (uint32_t k = it->second.first; k < it->second.second; ++k)
          fn(order_[k]);
      }
    }
  }

  // x offset from a to b, the short way round on the global tilings.
  double dx(double a, double b) const {
    double d = b - a;
    if (wrap_.width > 0) {
      if (d > wrap_.width / 2) d -= wrap_.width;
      if (d < -wrap_.width / 2) d += wrap_.width;
    }
    return d;
  }

 private:
  int64_t column(double x) const {
    const int64_t c = static_cast<int64_t>(std::floor((x - wrap_.west) / size_x_));
    return columns_ > 0 ? std::clamp<int64_t>(c, 0, columns_ - 1) : c;
  }
  int64_t row(double y) const { return static_cast<int64_t>(std::floor(y / size_y_)); }
  static uint64_t key(int64_t c, int64_t r) {
    return (static_cast<uint64_t>(c) << 32) ^ (static_cast<uint64_t>(r) & 0xffffffffu);
  }

  Wrap wrap_;
  double size_x_ = 1, size_y_ = 1;
  int64_t columns_ = 0;  // > 0: columns wrap
  std::vector<uint32_t> order_;
  std::unordered_map<uint64_t, std::pair<uint32_t, uint32_t>> cells_;
};

}  // namespace

PlaceSet merge_places(const PlaceSet& in, double radius, Wrap wrap) {
  const CellIndex index(in, radius, wrap);
  std::vector<uint32_t> order(in.size());
  std::iota(order.begin(), order.end(), uint32_t{0});
  std::vector<double> weights(in.size());
  for (size_t i = 0; i < in.size(); ++i)
    weights[i] = in.weight(i);
  std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
    return weights[a] != weights[b] ? weights[a] > weights[b] : in.id(a) < in.id(b);
  });
  const int fields = in.fields();
  std::vector<char> taken(in.size(), 0);
  PlaceSet out(fields);
  std::vector<double> sums(fields);
  std::vector<uint32_t> members;
  const double r2 = radius * radius;
  for (uint32_t i : order) {
    if (taken[i]) continue;
    members.clear();
    index.near(in.x(i), in.y(i), [&](uint32_t j) {
      if (taken[j]) return;
      const double dx = index.dx(in.x(i), in.x(j)), dy = in.y(j) - in.y(i);
      if (dx * dx + dy * dy <= r2) members.push_back(j);
    });
    // Members in index order, so the sums do not depend on the cells' order.
    std::sort(members.begin(), members.end());
    std::fill(sums.begin(), sums.end(), 0.0);
    double wx = 0, wy = 0, wsum = 0;
    uint64_t id = in.id(i);
    uint64_t count = 0;
    for (uint32_t j : members) {
      taken[j] = 1;
      const double w = weights[j];
      wx += w * index.dx(in.x(i), in.x(j));
      wy += w * (in.y(j) - in.y(i));
      wsum += w;
      id = std::min(id, in.id(j));
      count += in.count(j);
      for (int f = 0; f < fields; ++f)
        sums[f] += in.sums(j)[f];
    }
    double x = in.x(i) + wx / wsum;
    if (wrap.width > 0) {
      if (x < wrap.west) x += wrap.width;
      if (x >= wrap.west + wrap.width) x -= wrap.width;
    }
    out.add(x, in.y(i) + wy / wsum, id,
            static_cast<uint32_t>(std::min<uint64_t>(count, 0xfffffffeu)), sums);
  }
  return out;
}

double crowded_share(const PlaceSet& in, double radius, Wrap wrap) {
  if (in.size() == 0) return 0;
  const CellIndex index(in, radius, wrap);
  const double r2 = radius * radius;
  uint64_t crowded = 0;
  for (size_t i = 0; i < in.size(); ++i) {
    bool near = false;
    index.near(in.x(i), in.y(i), [&](uint32_t j) {
      if (near || j == i) return;
      const double dx = index.dx(in.x(i), in.x(j)), dy = in.y(j) - in.y(i);
      near = dx * dx + dy * dy <= r2;
    });
    crowded += near;
  }
  return double(crowded) / double(in.size());
}

}  // namespace globe
