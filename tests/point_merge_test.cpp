// The streamed place merge (docs/points.md "Aggregation"): band by band, with
// only undecided bands held, it gives what the greedy gives on all places at
// once - against a brute-force greedy written here (every pair, in merge
// order) on uniform, clustered, tied, stacked, chained and antimeridian
// places; its window stays a few bands; the crowded share against a count
// over every pair; and the place sorter's order with spills to disk.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "points/place_stream.hpp"
#include "points/point_aggregation.hpp"
#include "test_support.hpp"

namespace globe {
namespace {

struct Merged {
  double x, y;
  uint64_t id, count;
  std::vector<double> sums;
};

double weight_of(const Place& p) {
  double w = 0;
  for (double v : p.sums)
    w += std::fabs(v);
  return w > 0 ? w : double(p.count);
}

double offset(double from, double to, double width) {
  double d = to - from;
  if (width > 0 && d > width / 2) d -= width;
  if (width > 0 && d < -width / 2) d += width;
  return d;
}

// The greedy as docs/points.md states it, over every pair.
std::vector<Merged> brute_force(const std::vector<Place>& in, double r, Wrap wrap) {
  std::vector<size_t> order(in.size());
  for (size_t i = 0; i < in.size(); ++i)
    order[i] = i;
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    const double wa = weight_of(in[a]), wb = weight_of(in[b]);
    return wa != wb ? wa > wb : in[a].id < in[b].id;
  });
  std::vector<bool> taken(in.size());
  std::vector<Merged> out;
  for (size_t i : order) {
    if (taken[i]) continue;
    std::vector<size_t> members;
    for (size_t j = 0; j < in.size(); ++j) {
      const double dx = offset(in[i].x, in[j].x, wrap.width), dy = in[j].y - in[i].y;
      if (!taken[j] && dx * dx + dy * dy <= r * r) members.push_back(j);
    }
    std::sort(members.begin(), members.end(),
              [&](size_t a, size_t b) { return in[a].id < in[b].id; });
    Merged m{0, 0, in[i].id, 0, std::vector<double>(in[i].sums.size(), 0.0)};
    double wx = 0, wy = 0, ws = 0;
    for (size_t j : members) {
      taken[j] = true;
      const double w = weight_of(in[j]);
      wx += w * offset(in[i].x, in[j].x, wrap.width);
      wy += w * (in[j].y - in[i].y);
      ws += w;
      m.id = std::min(m.id, in[j].id);
      m.count += in[j].count;
      for (size_t f = 0; f < m.sums.size(); ++f)
        m.sums[f] += in[j].sums[f];
    }
    m.x = in[i].x + wx / ws;
    if (wrap.width > 0 && m.x < wrap.west) m.x += wrap.width;
    if (wrap.width > 0 && m.x >= wrap.west + wrap.width) m.x -= wrap.width;
    m.y = in[i].y + wy / ws;
    out.push_back(m);
  }
  std::sort(out.begin(), out.end(), [](const Merged& a, const Merged& b) { return a.id < b.id; });
  return out;
}

struct Streamed {
  std::vector<Merged> places;
  size_t peak = 0;
};

// The places in sweep order (north to south, ties by id), cut into bands of
// `band_height`, through a BandMerger.
Streamed streamed(std::vector<Place> in, double r, Wrap wrap, double band_height) {
  std::sort(in.begin(), in.end(),
            [](const Place& a, const Place& b) { return a.y != b.y ? a.y > b.y : a.id < b.id; });
  Streamed s;
  BandMerger merger(r, wrap, [&](const Place& p) {
    s.places.push_back({p.x, p.y, p.id, p.count, p.sums});
  });
  const double top = in.empty() ? 0 : in.front().y;
  std::vector<Place> band;
  int64_t current = 0;
  for (Place& p : in) {
    const int64_t b = static_cast<int64_t>(std::floor((top - p.y) / band_height));
    if (b != current && !band.empty()) {
      merger.add_band(current, std::move(band));
      band.clear();
    }
    current = b;
    band.push_back(p);
  }
  if (!band.empty()) merger.add_band(current, std::move(band));
  merger.finish();
  s.peak = merger.peak_places();
  std::sort(s.places.begin(), s.places.end(),
            [](const Merged& a, const Merged& b) { return a.id < b.id; });
  return s;
}

void expect_same(const std::vector<Merged>& want, const std::vector<Merged>& got,
                 const std::string& what) {
  ASSERT_EQ(got.size(), want.size()) << what;
  for (size_t i = 0; i < want.size(); ++i) {
    ASSERT_EQ(got[i].id, want[i].id) << what << " place " << i;
    EXPECT_EQ(got[i].count, want[i].count) << what << " id " << want[i].id;
    EXPECT_EQ(got[i].sums, want[i].sums) << what << " id " << want[i].id;
    EXPECT_NEAR(got[i].x, want[i].x, 1e-9 * (1 + std::fabs(want[i].x))) << what;
    EXPECT_NEAR(got[i].y, want[i].y, 1e-9 * (1 + std::fabs(want[i].y))) << what;
  }
}

Place place(double x, double y, uint64_t id, std::vector<double> sums) {
  Place p;
  p.x = x;
  p.y = y;
  p.id = id;
  p.sums = std::move(sums);
  return p;
}

std::vector<Place> random_places(int n, uint32_t seed, double size, bool clustered, int values) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0, size);
  std::normal_distribution<double> g(0, size / 60);
  std::vector<std::pair<double, double>> centres;
  for (int c = 0; c < 12; ++c)
    centres.emplace_back(u(rng), u(rng));
  std::vector<Place> out;
  for (int i = 0; i < n; ++i) {
    double x = u(rng), y = u(rng);
    if (clustered) {
      const auto& c = centres[rng() % centres.size()];
      x = c.first + g(rng);
      y = c.second + g(rng);
    }
    std::vector<double> sums;
    for (int f = 0; f < values; ++f)
      sums.push_back(double(rng() % 4));  // small integers: many ties, some all-zero places
    out.push_back(place(x, y, uint64_t(i + 1), sums));
  }
  return out;
}

TEST(PointMerge, StreamedMergeIsTheGreedyOnUniformAndClusteredPlaces) {
  for (bool clustered : {false, true})
    for (double r : {3.0, 11.0, 40.0})
      for (double band_factor : {1.0, 2.5, 7.0}) {
        const auto in = random_places(1500, 7 + uint32_t(r), 1000, clustered, 2);
        const std::string what = std::string(clustered ? "clustered" : "uniform") +
                                 " r=" + std::to_string(r) + " band=" + std::to_string(band_factor);
        expect_same(brute_force(in, r, {}), streamed(in, r, {}, r * band_factor).places, what);
      }
}

TEST(PointMerge, TiesStackedPlacesAndValuelessPlacesFollowTheOrder) {
  std::vector<Place> in;
  uint64_t id = 1;
  for (int i = 0; i < 30; ++i) {
    in.push_back(place(5, 5, id++, {1}));                // stacked, tied
    in.push_back(place(50 + i * 0.5, 20, id++, {0}));    // weight is the count
    in.push_back(place(100, 80 - i * 0.25, id++, {2}));  // a column across bands
  }
  for (double band : {1.0, 3.0})
    expect_same(brute_force(in, 1.0, {}), streamed(in, 1.0, {}, band).places,
                "band " + std::to_string(band));
}

// Weights grow along a line of places 0.9 radius apart running south: each
// place waits for the next, so the whole chain is decided only at its end.
TEST(PointMerge, AChainOfHeavierNeighboursAcrossEveryBandIsDecidedExactly) {
  std::vector<Place> in;
  for (int i = 0; i < 200; ++i)
    in.push_back(place(0.3 * i, -0.9 * i, uint64_t(i + 1), {double(i + 1)}));
  const auto s = streamed(in, 1.0, {}, 1.0);
  expect_same(brute_force(in, 1.0, {}), s.places, "chain");
  EXPECT_EQ(s.places.size(), 100u);  // every second place is a centre
}

TEST(PointMerge, NeighboursAcrossTheAntimeridianMerge) {
  const Wrap wrap{360, -180};
  std::vector<Place> in = random_places(800, 3, 30, true, 3);
  for (Place& p : in)
    p.x = p.x < 15 ? 180 - p.x * 0.1 : -180 + (p.x - 15) * 0.1;  // both edges
  const auto s = streamed(in, 0.4, wrap, 0.4);
  expect_same(brute_force(in, 0.4, wrap), s.places, "antimeridian");
  bool across = false;
  for (const Merged& m : s.places)
    across = across || m.count > 1;
  EXPECT_TRUE(across);
  for (const Merged& m : s.places) {
    EXPECT_GE(m.x, -180);
    EXPECT_LT(m.x, 180);
  }
}

TEST(PointMerge, TheWindowHoldsAFewBandsNotThePlaces) {
  const auto in = random_places(20000, 11, 1000, false, 1);
  const auto s = streamed(in, 2.0, {}, 2.0);
  // 500 bands of about 40 places: the window holds a handful of them.
  EXPECT_LT(s.peak, 400u);
  EXPECT_GT(s.places.size(), 1000u);
}

TEST(PointMerge, CrowdedShareCountsPlacesWithANeighbour) {
  globe_test::TempDir dir;
  const auto in = random_places(3000, 5, 1000, true, 1);
  std::vector<Place> sorted = in;
  std::sort(sorted.begin(), sorted.end(),
            [](const Place& a, const Place& b) { return a.y != b.y ? a.y > b.y : a.id < b.id; });
  PlaceFile file((dir / "places").string(), 1);
  for (const Place& p : sorted)
    file.append(p);
  for (double r : {0.5, 2.0, 9.0}) {
    size_t crowded = 0;
    for (size_t i = 0; i < in.size(); ++i)
      for (size_t j = 0; j < in.size(); ++j)
        if (i != j && std::hypot(in[i].x - in[j].x, in[i].y - in[j].y) <= r) {
          ++crowded;
          break;
        }
    file.rewind();
    const double top = sorted.front().y;
    const double got = crowded_share(file, r, {}, [&](const Place& p) {
      return static_cast<int64_t>(std::floor((top - p.y) / r));
    });
    EXPECT_DOUBLE_EQ(got, double(crowded) / double(in.size())) << "r=" << r;
  }
}

TEST(PointMerge, TheSorterReturnsPlacesNorthToSouthAndSpills) {
  globe_test::TempDir dir;
  auto in = random_places(5000, 9, 100, false, 4);
  for (size_t i = 0; i < 40; ++i)
    in[i].y = i % 2 ? 0.0 : -0.0;  // ties at zero, by id
  for (size_t i = 40; i < 80; ++i)
    in[i].y = -in[i].y;
  PlaceSorter sorter((dir / "sort").string(), 64 << 10, 4);
  std::vector<Place> shuffled = in;
  std::shuffle(shuffled.begin(), shuffled.end(), std::mt19937(1));
  for (const Place& p : shuffled)
    sorter.add(p);
  sorter.finish();
  std::vector<Place> want = in;
  std::sort(want.begin(), want.end(),
            [](const Place& a, const Place& b) { return a.y != b.y ? a.y > b.y : a.id < b.id; });
  Place p;
  size_t n = 0;
  while (sorter.next(p)) {
    ASSERT_LT(n, want.size());
    EXPECT_EQ(p.id, want[n].id) << n;
    EXPECT_EQ(p.x, want[n].x);
    EXPECT_EQ(p.sums, want[n].sums);
    ++n;
  }
  EXPECT_EQ(n, want.size());
}

}  // namespace
}  // namespace globe
