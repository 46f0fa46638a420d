// Choropleth classification and ColorBrewer ramps (tools/vectorize/areas/choropleth.hpp): the
// breaks against references written here from the methods' definitions (R's quantile type 7 by
// its formula, Jenks by exhaustive search of the partitions, R's pretty by outputs of R), class_of
// at the boundaries, and ColorBrewer's published colours.
#include "areas/choropleth.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <random>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

using globe::class_breaks;
using globe::class_of;
using globe::ClassMethod;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

std::vector<double> uniform_values(std::mt19937& rng, int n, double lo, double hi) {
  std::uniform_real_distribution<double> u(lo, hi);
  std::vector<double> v(n);
  for (double& x : v)
    x = u(rng);
  return v;
}

std::vector<double> sorted(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v;
}

std::vector<double> unique_sorted(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
  return v;
}

void expect_near_all(const std::vector<double>& got, const std::vector<double>& want, double tol) {
  ASSERT_EQ(got.size(), want.size());
  for (std::size_t i = 0; i < got.size(); ++i)
    EXPECT_NEAR(got[i], want[i], tol) << "break " << i;
}

// Sum of squared deviations from their mean of x[a, b), by two passes.
double ssd(const std::vector<double>& x, std::size_t a, std::size_t b) {
  double mean = 0;
  for (std::size_t i = a; i < b; ++i)
    mean += x[i];
  mean /= static_cast<double>(b - a);
  double s = 0;
  for (std::size_t i = a; i < b; ++i)
    s += (x[i] - mean) * (x[i] - mean);
  return s;
}

// Jenks by exhaustive search: every way of cutting sorted x into k non-empty contiguous classes.
// Returns the least cost and the class starts of a partition reaching it.
struct Partition {
  double cost = std::numeric_limits<double>::infinity();
  std::vector<std::size_t> starts;  // starts[0] = 0
};
Partition exhaustive_jenks(const std::vector<double>& x, std::size_t k) {
  Partition best;
  std::vector<std::size_t> starts{0};
  std::function<void(std::size_t, double)> go = [&](std::size_t from, double cost) {
    if (starts.size() == k) {
      const double total = cost + ssd(x, from, x.size());
      if (total < best.cost) best = {total, starts};
      return;
    }
    // The next class starts at s; each class keeps at least one value.
    for (std::size_t s = from + 1; s + (k - starts.size()) <= x.size(); ++s) {
      starts.push_back(s);
      go(s, cost + ssd(x, from, s));
      starts.pop_back();
    }
  };
  go(0, 0.0);
  return best;
}

// The Jenks breaks of a partition with classes closed on the left: min, the smallest value of
// each class but the first, max (the top class alone at the maximum: max twice).
std::vector<double> jenks_style_breaks(const std::vector<double>& x, const Partition& p) {
  std::vector<double> b{x.front()};
  for (std::size_t j = 1; j < p.starts.size(); ++j)
    b.push_back(x[p.starts[j]]);
  b.push_back(x.back());
  return b;
}

// The cost of the partition that Jenks breaks describe: class i holds [b_i, b_{i+1}), the last
// [b_{k-1}, b_k]; each class must be non-empty. `classes` is the number the partition had.
double cost_of_jenks_breaks(const std::vector<double>& x, const std::vector<double>& b,
                            std::size_t classes) {
  EXPECT_EQ(b.size(), classes + 1);
  const std::size_t k = b.size() - 1;
  std::vector<std::vector<double>> members(k);
  for (double v : x) {
    std::size_t c = k - 1;
    if (v != b[k])
      for (std::size_t i = 0; i < k; ++i)
        if (v >= b[i] && v < b[i + 1]) c = i;
    members[c].push_back(v);
  }
  double total = 0;
  for (const std::vector<double>& m : members) {
    EXPECT_FALSE(m.empty()) << "an empty class";
    if (m.empty()) continue;
    total += ssd(m, 0, m.size());
  }
  return total;
}

TEST(ChoroplethMethod, ParsesAndNamesEachMethod) {
  for (ClassMethod m :
       {ClassMethod::kQuantile, ClassMethod::kEqual, ClassMethod::kJenks, ClassMethod::kPretty}) {
    const auto parsed = globe::parse_class_method(globe::class_method_name(m));
    ASSERT_TRUE(parsed.has_value());
    EXPECT_EQ(*parsed, m);
  }
  EXPECT_EQ(std::string(globe::class_method_name(ClassMethod::kQuantile)), "quantile");
  EXPECT_EQ(std::string(globe::class_method_name(ClassMethod::kEqual)), "equal");
  EXPECT_EQ(std::string(globe::class_method_name(ClassMethod::kJenks)), "jenks");
  EXPECT_EQ(std::string(globe::class_method_name(ClassMethod::kPretty)), "pretty");
  EXPECT_FALSE(globe::parse_class_method("fisher").has_value());
  EXPECT_FALSE(globe::parse_class_method("").has_value());
  EXPECT_FALSE(globe::parse_class_method("quantiles").has_value());
}

TEST(ChoroplethQuantile, KnownType7Values) {
  // R: quantile(1:10, c(0, .25, .5, .75, 1)) is 1.00 3.25 5.50 7.75 10.00.
  const std::vector<double> v{10, 9, 8, 7, 6, 5, 4, 3, 2, 1};
  expect_near_all(class_breaks(v, 4, ClassMethod::kQuantile), {1, 3.25, 5.5, 7.75, 10}, 1e-12);
}

TEST(ChoroplethQuantile, MatchesType7ByItsFormula) {
  for (unsigned seed = 1; seed <= 6; ++seed) {
    std::mt19937 rng(seed);
    for (int n = 2; n <= 40; n += 3) {
      const std::vector<double> v = uniform_values(rng, n, -100, 100);
      const std::vector<double> x = sorted(v);
      for (int k = 2; k <= 12; ++k) {
        // Type 7: h = (n - 1) p + 1 (1-based), Q = x[floor h] + (h - floor h)(x[floor h + 1] -
        // x[floor h]).
        std::vector<double> want;
        for (int i = 0; i <= k; ++i) {
          const double p = static_cast<double>(i) / k;
          const double h = (n - 1) * p + 1;
          const auto lo = static_cast<std::size_t>(std::floor(h));
          const double below = x[lo - 1];
          const double above = x[std::min<std::size_t>(lo, n - 1)];
          want.push_back(below + (h - std::floor(h)) * (above - below));
        }
        SCOPED_TRACE("seed " + std::to_string(seed) + " n " + std::to_string(n) + " k " +
                     std::to_string(k));
        expect_near_all(class_breaks(v, k, ClassMethod::kQuantile), unique_sorted(want), 1e-9);
      }
    }
  }
}

TEST(ChoroplethEqual, MatchesMinPlusEqualSteps) {
  expect_near_all(class_breaks(std::vector<double>{10, 0, 3}, 5, ClassMethod::kEqual),
                  {0, 2, 4, 6, 8, 10}, 1e-12);
  for (unsigned seed = 1; seed <= 6; ++seed) {
    std::mt19937 rng(seed);
    const std::vector<double> v = uniform_values(rng, 50, -1e3, 5e3);
    const double lo = *std::min_element(v.begin(), v.end());
    const double hi = *std::max_element(v.begin(), v.end());
    for (int k = 2; k <= 12; ++k) {
      std::vector<double> want;
      for (int i = 0; i <= k; ++i)
        want.push_back(lo + i * (hi - lo) / k);
      const std::vector<double> got = class_breaks(v, k, ClassMethod::kEqual);
      expect_near_all(got, want, 1e-9);
      ASSERT_FALSE(got.empty());
      EXPECT_EQ(got.front(), lo);
      EXPECT_EQ(got.back(), hi);
    }
  }
}

TEST(ChoroplethJenks, MatchesExhaustiveSearch) {
  for (unsigned seed = 1; seed <= 8; ++seed) {
    std::mt19937 rng(seed);
    for (int n = 2; n <= 12; ++n) {
      const std::vector<double> v = uniform_values(rng, n, -50, 50);
      const std::vector<double> x = sorted(v);
      for (int k = 2; k <= 4; ++k) {
        SCOPED_TRACE("seed " + std::to_string(seed) + " n " + std::to_string(n) + " k " +
                     std::to_string(k));
        const std::size_t classes = std::min<std::size_t>(k, x.size());
        const Partition best = exhaustive_jenks(x, classes);
        const std::vector<double> got = class_breaks(v, k, ClassMethod::kJenks);
        // Distinct random values: the optimum is unique and its breaks are data values.
        EXPECT_EQ(got, jenks_style_breaks(x, best));
        EXPECT_NEAR(cost_of_jenks_breaks(x, got, classes), best.cost, 1e-9 * (1 + best.cost));
      }
    }
  }
}

TEST(ChoroplethJenks, RepeatedValuesReachTheLeastCost) {
  for (unsigned seed = 1; seed <= 8; ++seed) {
    std::mt19937 rng(seed);
    std::uniform_int_distribution<int> d(0, 6);
    for (int n = 3; n <= 12; ++n) {
      std::vector<double> v(n);
      for (double& x : v)
        x = d(rng);
      const std::vector<double> x = sorted(v);
      const std::size_t distinct = unique_sorted(v).size();
      if (distinct < 2) continue;
      for (int k = 2; k <= 4; ++k) {
        SCOPED_TRACE("seed " + std::to_string(seed) + " n " + std::to_string(n) + " k " +
                     std::to_string(k));
        const std::size_t classes = std::min<std::size_t>(k, distinct);
        const Partition best = exhaustive_jenks(x, classes);
        const std::vector<double> got = class_breaks(v, k, ClassMethod::kJenks);
        EXPECT_TRUE(std::is_sorted(got.begin(), got.end()));
        // Strictly increasing, but for a top class of the maximum alone.
        EXPECT_EQ(std::adjacent_find(got.begin(), got.end() - 1), got.end() - 1);
        EXPECT_NEAR(cost_of_jenks_breaks(x, got, classes), best.cost, 1e-9 * (1 + best.cost));
      }
    }
  }
}

// Least within-class sum of squared deviations of sorted x in k classes, by the plain O(n^2 k)
// programme over every value (no grouping of repeated values).
double plain_programme_cost(const std::vector<double>& x, std::size_t k) {
  const std::size_t n = x.size();
  std::vector<double> s1(n + 1, 0), s2(n + 1, 0);
  for (std::size_t i = 0; i < n; ++i) {
    s1[i + 1] = s1[i] + x[i];
    s2[i + 1] = s2[i] + x[i] * x[i];
  }
  auto cost = [&](std::size_t a, std::size_t b) {
    const double d = s1[b] - s1[a];
    return (s2[b] - s2[a]) - d * d / static_cast<double>(b - a);
  };
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<std::vector<double>> f(k + 1, std::vector<double>(n + 1, inf));
  f[0][0] = 0;
  for (std::size_t j = 1; j <= k; ++j) {
    for (std::size_t i = j; i <= n; ++i) {
      for (std::size_t t = j - 1; t < i; ++t)
        f[j][i] = std::min(f[j][i], f[j - 1][t] + cost(t, i));
    }
  }
  return f[k][n];
}

TEST(ChoroplethJenks, LargerDataMatchThePlainProgramme) {
  for (unsigned seed = 1; seed <= 3; ++seed) {
    std::mt19937 rng(seed);
    // Repeated values (grouped and weighted by the implementation), and distinct clustered ones.
    std::uniform_int_distribution<int> d(0, 60);
    std::vector<double> repeats(400);
    for (double& x : repeats)
      x = d(rng) * 0.5 + (d(rng) % 3 == 0 ? 30 : 0);
    std::vector<double> clustered;
    for (double centre : {-20.0, 0.0, 3.0, 40.0, 41.0, 100.0}) {
      std::normal_distribution<double> g(centre, 1.0 + std::fabs(centre) / 20);
      for (int i = 0; i < 50; ++i)
        clustered.push_back(g(rng));
    }
    for (const std::vector<double>* v : {&repeats, &clustered}) {
      const std::vector<double> x = sorted(*v);
      const std::size_t distinct = unique_sorted(*v).size();
      for (int k = 2; k <= 12; ++k) {
        SCOPED_TRACE("seed " + std::to_string(seed) + " k " + std::to_string(k) +
                     (v == &repeats ? " repeats" : " clustered"));
        const std::size_t classes = std::min<std::size_t>(k, distinct);
        const double want = plain_programme_cost(x, classes);
        const std::vector<double> got = class_breaks(*v, k, ClassMethod::kJenks);
        EXPECT_NEAR(cost_of_jenks_breaks(x, got, classes), want, 1e-7 * (1 + want));
      }
    }
  }
}

TEST(ChoroplethJenks, ManyDistinctValuesUseTheSampledProgramme) {
  std::mt19937 rng(42);
  std::vector<double> v = uniform_values(rng, 100000, -1000, 1000);
  std::exponential_distribution<double> e(0.01);
  for (int i = 0; i < 20000; ++i)
    v[i] = e(rng);  // a skewed part, so the classes differ in width
  const std::vector<double> got = class_breaks(v, 7, ClassMethod::kJenks);
  ASSERT_EQ(got.size(), 8u);
  EXPECT_TRUE(std::is_sorted(got.begin(), got.end()));
  EXPECT_EQ(std::adjacent_find(got.begin(), got.end()), got.end());
  EXPECT_EQ(got.front(), *std::min_element(v.begin(), v.end()));
  EXPECT_EQ(got.back(), *std::max_element(v.begin(), v.end()));
  // The breaks are order statistics: values of the data.
  const std::set<double> values(v.begin(), v.end());
  for (double b : got)
    EXPECT_TRUE(values.count(b)) << b;
}

TEST(ChoroplethPretty, KnownROutputs) {
  auto pretty = [](std::vector<double> v, int n) {
    return class_breaks(v, n, ClassMethod::kPretty);
  };
  // R: pretty(c(1, 99)), pretty(c(0, 100)), pretty(1:10), pretty(c(0.13, 0.87), 5),
  // pretty(c(0, 1)), pretty(c(-1, 1)), pretty(c(-3.2, 7.9), 4).
  expect_near_all(pretty({1, 99}, 5), {0, 20, 40, 60, 80, 100}, 1e-12);
  expect_near_all(pretty({0, 100}, 5), {0, 20, 40, 60, 80, 100}, 1e-12);
  expect_near_all(pretty({1, 2, 3, 4, 5, 6, 7, 8, 9, 10}, 5), {0, 2, 4, 6, 8, 10}, 1e-12);
  expect_near_all(pretty({0.13, 0.5, 0.87}, 5), {0, 0.2, 0.4, 0.6, 0.8, 1.0}, 1e-12);
  expect_near_all(pretty({0, 1}, 5), {0, 0.2, 0.4, 0.6, 0.8, 1.0}, 1e-12);
  expect_near_all(pretty({-1, 1}, 5), {-1, -0.5, 0, 0.5, 1}, 1e-12);
  expect_near_all(pretty({-3.2, 7.9}, 4), {-4, -2, 0, 2, 4, 6, 8}, 1e-12);
  // R zaps the seq() rounding error at zero: an exact 0, not 1e-17.
  const std::vector<double> around_zero = pretty({-0.3, 0.7}, 5);
  EXPECT_NE(std::find(around_zero.begin(), around_zero.end(), 0.0), around_zero.end());
}

TEST(ChoroplethPretty, BreaksAreRoundStepsCoveringTheRange) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> exponent(-6, 8), unit(-1, 1);
  for (int trial = 0; trial < 300; ++trial) {
    const double scale = std::pow(10.0, exponent(rng));
    std::vector<double> v{unit(rng) * scale, unit(rng) * scale, unit(rng) * scale};
    const double lo = *std::min_element(v.begin(), v.end());
    const double hi = *std::max_element(v.begin(), v.end());
    const int n = 2 + trial % 11;
    const std::vector<double> b = class_breaks(v, n, ClassMethod::kPretty);
    SCOPED_TRACE("trial " + std::to_string(trial));
    ASSERT_GE(b.size(), 2u);
    const double step = (b.back() - b.front()) / static_cast<double>(b.size() - 1);
    EXPECT_LE(b.front(), lo);
    EXPECT_GE(b.back(), hi);
    EXPECT_GT(b.front(), lo - step * (1 + 1e-9));
    EXPECT_LT(b.back(), hi + step * (1 + 1e-9));
    // The step is 1, 2 or 5 times a power of ten; every break a multiple of it.
    const double mantissa = step / std::pow(10.0, std::floor(std::log10(step)));
    EXPECT_TRUE(std::fabs(mantissa - 1) < 1e-6 || std::fabs(mantissa - 2) < 1e-6 ||
                std::fabs(mantissa - 5) < 1e-6 || std::fabs(mantissa - 10) < 1e-6)
        << "step " << step;
    for (std::size_t i = 0; i < b.size(); ++i) {
      EXPECT_NEAR(b[i], b.front() + step * static_cast<double>(i), step * 1e-9);
      EXPECT_NEAR(b[i] / step, std::round(b[i] / step), 1e-6);
    }
    // About n classes: R's unit keeps cell/unit within (0.56, 1.4], so (up to the rounding of the
    // ends) between 0.56 n and 1.4 n + 2 classes.
    const auto k = static_cast<double>(b.size() - 1);
    EXPECT_GE(k, std::floor(0.56 * n));
    EXPECT_LE(k, 1.4 * n + 2);
  }
}

TEST(ChoroplethClassOf, LeftClosedWithTheLastClassClosed) {
  const std::vector<double> b{0, 1, 2, 3};
  EXPECT_EQ(class_of(0, b), 0);
  EXPECT_EQ(class_of(0.5, b), 0);
  EXPECT_EQ(class_of(std::nextafter(1.0, 0.0), b), 0);
  EXPECT_EQ(class_of(1, b), 1);
  EXPECT_EQ(class_of(2, b), 2);
  EXPECT_EQ(class_of(2.999, b), 2);
  EXPECT_EQ(class_of(3, b), 2);
  EXPECT_EQ(class_of(-0.001, b), -1);
  EXPECT_EQ(class_of(std::nextafter(3.0, 4.0), b), -1);
  EXPECT_EQ(class_of(kNaN, b), -1);
  EXPECT_EQ(class_of(kInf, b), -1);
  EXPECT_EQ(class_of(-kInf, b), -1);
  EXPECT_EQ(class_of(1, std::vector<double>{}), -1);
  EXPECT_EQ(class_of(1, std::vector<double>{1}), -1);
  // One class holding a single value.
  EXPECT_EQ(class_of(5, std::vector<double>{5, 5}), 0);
  EXPECT_EQ(class_of(5.5, std::vector<double>{5, 5}), -1);
}

TEST(ChoroplethClassOf, EveryValueFallsInAClassOfEveryMethod) {
  std::mt19937 rng(11);
  std::vector<double> v = uniform_values(rng, 200, -5, 20);
  for (int i = 0; i < 50; ++i)
    v[i] = std::round(v[i]);  // some repeats
  for (ClassMethod m :
       {ClassMethod::kQuantile, ClassMethod::kEqual, ClassMethod::kJenks, ClassMethod::kPretty}) {
    for (int k = 2; k <= 12; ++k) {
      const std::vector<double> b = class_breaks(v, k, m);
      ASSERT_GE(b.size(), 2u);
      EXPECT_EQ(std::adjacent_find(b.begin(), b.end(), std::greater_equal<double>()), b.end())
          << globe::class_method_name(m) << " " << k << ": breaks not strictly increasing";
      const int classes = static_cast<int>(b.size()) - 1;
      for (double x : v) {
        const int c = class_of(x, b);
        EXPECT_GE(c, 0) << globe::class_method_name(m) << " " << k << " " << x;
        EXPECT_LT(c, classes);
      }
    }
  }
}

TEST(ChoroplethBreaks, RepeatedValuesCollapseBreaks) {
  // Type 7 quantiles of eight 1s, a 2 and a 3 at 0, .25, .5, .75, 1: 1 1 1 1 3.
  const std::vector<double> v{1, 1, 1, 1, 1, 1, 1, 1, 2, 3};
  EXPECT_EQ(class_breaks(v, 4, ClassMethod::kQuantile), (std::vector<double>{1, 3}));
  // Two distinct values: Jenks can make only two one-value classes, [1, 3) and [3, 3].
  const std::vector<double> two{1, 1, 3, 3, 1};
  EXPECT_EQ(class_breaks(two, 5, ClassMethod::kJenks), (std::vector<double>{1, 3, 3}));
  // Three distinct values in 3 or more classes: every value its own class.
  const std::vector<double> three{4, 2, 9, 2, 4, 9, 9};
  EXPECT_EQ(class_breaks(three, 3, ClassMethod::kJenks), (std::vector<double>{2, 4, 9, 9}));
  EXPECT_EQ(class_breaks(three, 7, ClassMethod::kJenks), (std::vector<double>{2, 4, 9, 9}));
  EXPECT_EQ(globe::class_of(9, class_breaks(three, 3, ClassMethod::kJenks)), 2);
  EXPECT_EQ(globe::class_of(4, class_breaks(three, 3, ClassMethod::kJenks)), 1);
  EXPECT_EQ(class_breaks(three, 7, ClassMethod::kEqual).size(), 8u);
}

TEST(ChoroplethBreaks, OneDistinctValueIsOneClass) {
  const std::vector<double> v{5, 5, kNaN, 5, kInf};
  for (ClassMethod m :
       {ClassMethod::kQuantile, ClassMethod::kEqual, ClassMethod::kJenks, ClassMethod::kPretty}) {
    const std::vector<double> b = class_breaks(v, 4, m);
    EXPECT_EQ(b, (std::vector<double>{5, 5})) << globe::class_method_name(m);
    EXPECT_EQ(class_of(5, b), 0);
  }
  EXPECT_EQ(class_breaks(std::vector<double>{-2.5}, 3, ClassMethod::kJenks),
            (std::vector<double>{-2.5, -2.5}));
}

TEST(ChoroplethBreaks, NonFiniteValuesAreSkipped) {
  std::mt19937 rng(3);
  const std::vector<double> clean = uniform_values(rng, 30, 0, 10);
  std::vector<double> dirty = clean;
  dirty.insert(dirty.begin() + 5, kNaN);
  dirty.push_back(kInf);
  dirty.push_back(-kInf);
  dirty.insert(dirty.begin(), kNaN);
  for (ClassMethod m :
       {ClassMethod::kQuantile, ClassMethod::kEqual, ClassMethod::kJenks, ClassMethod::kPretty}) {
    EXPECT_EQ(class_breaks(dirty, 5, m), class_breaks(clean, 5, m)) << globe::class_method_name(m);
  }
}

TEST(ChoroplethBreaks, RejectsBadClassCountsAndNoFiniteValue) {
  const std::vector<double> v{1, 2, 3};
  for (ClassMethod m :
       {ClassMethod::kQuantile, ClassMethod::kEqual, ClassMethod::kJenks, ClassMethod::kPretty}) {
    for (int k : {-1, 0, 1, 13, 100}) {
      EXPECT_THROW(class_breaks(v, k, m), std::invalid_argument) << k;
    }
    EXPECT_NO_THROW(class_breaks(v, 2, m));
    EXPECT_NO_THROW(class_breaks(v, 12, m));
    EXPECT_THROW(class_breaks(std::vector<double>{}, 5, m), std::invalid_argument);
    EXPECT_THROW(class_breaks(std::vector<double>{kNaN, kInf, -kInf}, 5, m), std::invalid_argument);
  }
}

using Colours = std::vector<std::string>;

TEST(ChoroplethRamps, KnownColorBrewerColours) {
  EXPECT_EQ(globe::ramp_colors("YlOrRd", 3), (Colours{"#ffeda0", "#feb24c", "#f03b20"}));
  EXPECT_EQ(globe::ramp_colors("Blues", 5),
            (Colours{"#eff3ff", "#bdd7e7", "#6baed6", "#3182bd", "#08519c"}));
  EXPECT_EQ(globe::ramp_colors("RdBu", 3), (Colours{"#ef8a62", "#f7f7f7", "#67a9cf"}));
  // ColorBrewer's PuOr runs from orange to purple.
  EXPECT_EQ(globe::ramp_colors("PuOr", 3), (Colours{"#f1a340", "#f7f7f7", "#998ec3"}));
  const auto greys = globe::ramp_colors("Greys", 9);
  ASSERT_TRUE(greys.has_value());
  EXPECT_EQ(greys->front(), "#ffffff");
  EXPECT_EQ(greys->back(), "#000000");
  const auto ylorrd = globe::ramp_colors("YlOrRd", 9);
  ASSERT_TRUE(ylorrd.has_value());
  EXPECT_EQ(ylorrd->back(), "#800026");
  const auto spectral = globe::ramp_colors("Spectral", 11);
  ASSERT_TRUE(spectral.has_value());
  EXPECT_EQ(spectral->front(), "#9e0142");
  EXPECT_EQ((*spectral)[5], "#ffffbf");
  EXPECT_EQ(spectral->back(), "#5e4fa2");
}

TEST(ChoroplethRamps, NamesAreMatchedIgnoringCase) {
  EXPECT_EQ(globe::ramp_colors("ylorrd", 3), globe::ramp_colors("YlOrRd", 3));
  EXPECT_EQ(globe::ramp_colors("BLUES", 5), globe::ramp_colors("Blues", 5));
  EXPECT_EQ(globe::ramp_colors("rdbu", 7), globe::ramp_colors("RdBu", 7));
  EXPECT_TRUE(globe::ramp_colors("prgn", 11).has_value());
}

TEST(ChoroplethRamps, UnknownNamesAndClassCounts) {
  EXPECT_FALSE(globe::ramp_colors("Viridis", 5).has_value());
  EXPECT_FALSE(globe::ramp_colors("", 5).has_value());
  EXPECT_FALSE(globe::ramp_colors("Blue", 5).has_value());
  EXPECT_FALSE(globe::ramp_colors("Blues", 2).has_value());
  EXPECT_FALSE(globe::ramp_colors("Blues", 10).has_value());
  EXPECT_FALSE(globe::ramp_colors("RdBu", 12).has_value());
  EXPECT_FALSE(globe::ramp_colors("RdBu", 0).has_value());
  EXPECT_FALSE(globe::ramp_colors("RdBu", -3).has_value());
}

int lightness(const std::string& hex) {
  return std::stoi(hex.substr(1, 2), nullptr, 16) + std::stoi(hex.substr(3, 2), nullptr, 16) +
         std::stoi(hex.substr(5, 2), nullptr, 16);
}

TEST(ChoroplethRamps, EveryRampHasEveryClassCountInItsRange) {
  const std::set<std::string> sequential{"YlOrRd",  "YlOrBr", "YlGnBu", "YlGn", "Reds", "RdPu",
                                         "Purples", "PuRd",   "PuBuGn", "PuBu", "OrRd", "Oranges",
                                         "Greys",   "Greens", "GnBu",   "BuPu", "BuGn", "Blues"};
  const std::set<std::string> diverging{"Spectral", "RdYlGn", "RdYlBu", "RdGy", "RdBu",
                                        "PuOr",     "PRGn",   "PiYG",   "BrBG"};
  std::set<std::string> seen_sequential, seen_diverging;
  for (const globe::ColorRamp& r : globe::color_ramps()) {
    const std::string name = r.name;
    SCOPED_TRACE(name);
    (r.type == globe::RampType::kSequential ? seen_sequential : seen_diverging).insert(name);
    EXPECT_EQ(r.min_classes, 3);
    EXPECT_EQ(r.max_classes, r.type == globe::RampType::kSequential ? 9 : 11);
    EXPECT_FALSE(globe::ramp_colors(name, r.min_classes - 1).has_value());
    EXPECT_FALSE(globe::ramp_colors(name, r.max_classes + 1).has_value());
    for (int k = r.min_classes; k <= r.max_classes; ++k) {
      const auto colours = globe::ramp_colors(name, k);
      ASSERT_TRUE(colours.has_value()) << k;
      ASSERT_EQ(colours->size(), static_cast<std::size_t>(k));
      for (const std::string& c : *colours) {
        ASSERT_EQ(c.size(), 7u) << c;
        EXPECT_EQ(c[0], '#');
        EXPECT_EQ(c.find_first_not_of("0123456789abcdef", 1), std::string::npos) << c;
      }
      EXPECT_EQ(std::set<std::string>(colours->begin(), colours->end()).size(), colours->size())
          << k << ": repeated colours";
      if (r.type == globe::RampType::kSequential) {
        EXPECT_GT(lightness(colours->front()), lightness(colours->back())) << k;
      } else {
        // Light in the middle, dark at both ends.
        const int middle = lightness((*colours)[k / 2]);
        EXPECT_GT(middle, lightness(colours->front())) << k;
        EXPECT_GT(middle, lightness(colours->back())) << k;
      }
    }
  }
  EXPECT_EQ(seen_sequential, sequential);
  EXPECT_EQ(seen_diverging, diverging);
}

}  // namespace
