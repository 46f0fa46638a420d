// Choropleth classification (quantile, equal, Jenks, pretty breaks) and the ColorBrewer ramps.
// Colours from ColorBrewer 2.0 by Cynthia A. Brewer, Penn State (Apache License 2.0).
#include "areas/choropleth.hpp"

#include <algorithm>
#include <array>
#include <cfloat>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <stdexcept>

namespace globe {
namespace {

// The finite values, sorted.
std::vector<double> finite_sorted(std::span<const double> values) {
  std::vector<double> x;
  x.reserve(values.size());
  for (double v : values) {
    if (std::isfinite(v)) x.push_back(v);
  }
  std::sort(x.begin(), x.end());
  return x;
}

// Rounding can leave a break an ulp below its predecessor: make them non-decreasing, then drop
// the repeated ones.
std::vector<double> monotone_unique(std::vector<double> b) {
  for (std::size_t i = 1; i < b.size(); ++i)
    b[i] = std::max(b[i], b[i - 1]);
  b.erase(std::unique(b.begin(), b.end()), b.end());
  return b;
}

// R's quantile(x, p, type = 7) of sorted x, as R computes it: index = 1 + (n - 1) p,
// (1 - h) x[lo] + h x[hi] with h the fractional part.
double quantile7(const std::vector<double>& x, double p) {
  const double index = 1.0 + static_cast<double>(x.size() - 1) * p;
  const double lo = std::floor(index);
  const auto ilo = static_cast<std::size_t>(lo) - 1;
  const auto ihi = std::min(static_cast<std::size_t>(std::ceil(index)) - 1, x.size() - 1);
  double q = x[ilo];
  if (index > lo && x[ihi] != q) {
    const double h = index - lo;
    q = (1.0 - h) * q + h * x[ihi];
  }
  return q;
}

std::vector<double> quantile_breaks(const std::vector<double>& x, int classes) {
  // seq(0, 1, 1/n) is from + (0:n) * by, capped at to.
  const double by = 1.0 / classes;
  std::vector<double> b;
  for (int i = 0; i <= classes; ++i)
    b.push_back(quantile7(x, std::min(i * by, 1.0)));
  return b;
}

// seq(lo, hi, length.out = n + 1) as R's seq.int computes it: the ends exact, lo + i * by between.
std::vector<double> linear_breaks(double lo, double hi, int n) {
  double by = (hi - lo) / n;
  if (!std::isfinite(by)) by = hi / n - lo / n;
  std::vector<double> b(n + 1);
  b[0] = lo;
  for (int i = 1; i < n; ++i)
    b[i] = lo + i * by;
  b[n] = hi;
  return b;
}

// Jenks natural breaks by Fisher's dynamic programme over the sorted distinct values v with
// weights w (counts): the partition into `classes` contiguous classes of least total within-class
// weighted sum of squared deviations. Returns the breaks: min, the smallest value of each class
// but the first, max (twice if the top class is the maximum alone).
std::vector<double> jenks_weighted(const std::vector<double>& v, const std::vector<double>& w,
                                   int classes) {
  const std::size_t m = v.size();
  const std::size_t k = std::min<std::size_t>(classes, m);
  if (k == m) {  // every distinct value a class of its own; the top one [max, max]
    std::vector<double> b = v;
    if (m > 1) b.push_back(v.back());
    return b;
  }
  // Centred on the middle of the range and scaled to [-1, 1]: the costs neither overflow nor lose
  // their digits to a large offset, and a positive factor leaves the optimum where it is.
  const double centre = v.front() / 2 + v.back() / 2;
  const double scale = v.back() / 2 - v.front() / 2;
  std::vector<double> sw(m + 1, 0.0), s1(m + 1, 0.0), s2(m + 1, 0.0);
  for (std::size_t i = 0; i < m; ++i) {
    const double u = (v[i] - centre) / scale;
    sw[i + 1] = sw[i] + w[i];
    s1[i + 1] = s1[i] + w[i] * u;
    s2[i + 1] = s2[i] + w[i] * u * u;
  }
  // Sum of squared deviations of items [a, b).
  auto cost = [&](std::size_t a, std::size_t b) {
    const double d1 = s1[b] - s1[a];
    return std::max(0.0, (s2[b] - s2[a]) - d1 * d1 / (sw[b] - sw[a]));
  };
  // best[i]: least cost of the first i items in j - 1 classes; next[i] the same in j classes, and
  // start[j][i] where the last of those j classes starts. Class j (1-based) of the final partition
  // ends at an item index in [j, m - (k - j)].
  std::vector<double> best(m + 1), next(m + 1);
  std::vector<std::vector<std::uint32_t>> start(k + 1, std::vector<std::uint32_t>(m + 1, 0));
  for (std::size_t i = 1; i <= m; ++i)
    best[i] = cost(0, i);
  // The within-class sum of squares of sorted values satisfies the quadrangle inequality, so the
  // (leftmost) best start of the last class never decreases as i grows: solving the middle i
  // first bounds the starts of those on either side (divide and conquer), O(m log m) per class
  // count instead of O(m^2), and still exact.
  struct Range {
    std::size_t i_lo, i_hi, t_lo, t_hi;
  };
  std::vector<Range> todo;
  for (std::size_t j = 2; j <= k; ++j) {
    todo.push_back({j, m - (k - j), j - 1, m - (k - j) - 1});
    while (!todo.empty()) {
      const Range r = todo.back();
      todo.pop_back();
      const std::size_t i = r.i_lo + (r.i_hi - r.i_lo) / 2;
      double lowest = INFINITY;
      std::size_t at = r.t_lo;
      for (std::size_t t = r.t_lo; t <= std::min(r.t_hi, i - 1); ++t) {
        const double c = best[t] + cost(t, i);
        if (c < lowest) {
          lowest = c;
          at = t;
        }
      }
      next[i] = lowest;
      start[j][i] = static_cast<std::uint32_t>(at);
      if (i > r.i_lo) todo.push_back({r.i_lo, i - 1, r.t_lo, at});
      if (i < r.i_hi) todo.push_back({i + 1, r.i_hi, at, r.t_hi});
    }
    std::swap(best, next);
  }
  // Walk back from the last class: the class before each start ends at item start - 1.
  std::vector<double> b(k + 1);
  b[0] = v.front();
  b[k] = v.back();
  std::size_t end = m;
  for (std::size_t j = k; j >= 2; --j) {
    end = start[j][end];
    b[j - 1] = v[end];  // class j's smallest value: its lower bound
  }
  return b;
}

// At most this many distinct values go into the programme.
constexpr std::size_t kJenksMaxDistinct = 5000;

std::vector<double> jenks_breaks(const std::vector<double>& x, int classes) {
  std::size_t distinct = 1;
  for (std::size_t i = 1; i < x.size(); ++i)
    distinct += x[i] != x[i - 1];
  std::vector<double> sample;
  const std::vector<double>* data = &x;
  if (distinct > kJenksMaxDistinct) {
    // Order statistics at evenly spaced ranks, the first and last the minimum and maximum.
    sample.resize(kJenksMaxDistinct);
    const double step = static_cast<double>(x.size() - 1) / (kJenksMaxDistinct - 1);
    for (std::size_t i = 0; i < kJenksMaxDistinct; ++i) {
      const auto r = static_cast<std::size_t>(std::llround(i * step));
      sample[i] = x[std::min(r, x.size() - 1)];
    }
    data = &sample;
  }
  std::vector<double> v, w;
  for (double d : *data) {
    if (!v.empty() && v.back() == d) {
      w.back() += 1.0;
    } else {
      v.push_back(d);
      w.push_back(1.0);
    }
  }
  return jenks_weighted(v, w, classes);
}

// R's R_pretty (src/appl/pretty.c) with return_bounds = TRUE and eps_correction = 0: widens
// [lo, up] to multiples of a round unit (1, 2 or 5 times a power of ten) and sets ndiv to the
// number of units between them.
void r_pretty(double& lo, double& up, int& ndiv, int min_n) {
  constexpr double kShrinkSml = 0.75;
  constexpr double kH = 1.5;               // high.u.bias
  constexpr double kH5 = 0.5 + 1.5 * kH;   // u5.bias
  constexpr double kFMin = 1.0 / 1048576;  // f.min = 2^-20
  constexpr double kRoundingEps = 1e-10;
  const double lo0 = lo, up0 = up, dx = up0 - lo0;
  double cell;
  bool i_small;
  if (dx == 0 && up0 == 0) {
    cell = 1;
    i_small = true;
  } else {
    cell = std::max(std::fabs(lo0), std::fabs(up0));
    double u = 1 + ((kH5 >= 1.5 * kH + 0.5) ? 1 / (1 + kH) : 1.5 / (1 + kH5));
    u *= std::max(1, ndiv) * DBL_EPSILON;
    i_small = dx < cell * u * 3;
  }
  if (i_small) {
    if (cell > 10) cell = 9 + cell / 10;
    cell *= kShrinkSml;
    if (min_n > 1) cell /= min_n;
  } else {
    cell = dx;
    if (std::isfinite(dx)) {
      if (ndiv > 1) cell /= ndiv;
    } else if (ndiv >= 2) {
      cell = up0 / ndiv - lo0 / ndiv;
    }
  }
  const double subsmall = kFMin * DBL_MIN;
  if (cell < subsmall) {
    cell = subsmall;
  } else if (cell > DBL_MAX / 1.25) {
    cell = DBL_MAX / 1.25;
  }
  const double base = std::pow(10.0, std::floor(std::log10(cell)));
  double unit = base;
  if (2 * base - cell < kH * (cell - unit)) {
    unit = 2 * base;
    if (5 * base - cell < kH5 * (cell - unit)) {
      unit = 5 * base;
      if (10 * base - cell < kH * (cell - unit)) unit = 10 * base;
    }
  }
  double ns = std::floor(lo0 / unit + kRoundingEps);
  double nu = std::ceil(up0 / unit - kRoundingEps);
  while (ns * unit > lo + kRoundingEps * unit)
    ns--;
  while (!std::isfinite(ns * unit))
    ns++;
  while (nu * unit < up - kRoundingEps * unit)
    nu++;
  while (!std::isfinite(nu * unit))
    nu--;
  int k = static_cast<int>(0.5 + nu - ns);
  if (k < min_n) {
    k = min_n - k;
    if (lo0 == 0 && ns == 0 && up0 != 0) {
      nu += k;
    } else if (up0 == 0 && nu == 0 && lo0 != 0) {
      ns -= k;
    } else if (ns >= 0) {
      nu += k / 2;
      ns -= k / 2 + k % 2;
    } else {
      ns -= k / 2;
      nu += k / 2 + k % 2;
    }
    ndiv = min_n;
  } else {
    ndiv = k;
  }
  if (ns * unit < lo) lo = ns * unit;
  if (nu * unit > up) up = nu * unit;
}

// R's pretty.default(c(lo, up), n): R_pretty, then seq.int(l, u, length.out = n + 1) with the
// values within 1e-14 of a step of zero set to zero.
std::vector<double> pretty_breaks(double lo, double up, int n) {
  int ndiv = n;
  r_pretty(lo, up, ndiv, n / 3);
  if (ndiv < 1) return {lo, up};
  std::vector<double> b = linear_breaks(lo, up, ndiv);
  const double delta = up / ndiv - lo / ndiv;
  for (double& s : b) {
    if (std::fabs(s) < 1e-14 * delta) s = 0;
  }
  return b;
}

bool equal_ignoring_case(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    auto lower = [](char c) {
      return (c >= 'A' && c <= 'Z') ? static_cast<char>(c - 'A' + 'a') : c;
    };
    if (lower(a[i]) != lower(b[i])) return false;
  }
  return true;
}

// One ColorBrewer scheme: colours[i] holds the 3 + i colours of the (3 + i)-class ramp as
// consecutive 6-digit hex groups; sequential ramps have 3..9 classes, diverging 3..11.
struct RampTable {
  const char* name;
  RampType type;
  std::array<const char*, 9> colours;
};

// clang-format off
constexpr RampTable kRamps[] = {
  {"YlOrRd", RampType::kSequential,
   {"ffeda0feb24cf03b20",
    "ffffb2fecc5cfd8d3ce31a1c",
    "ffffb2fecc5cfd8d3cf03b20bd0026",
    "ffffb2fed976feb24cfd8d3cf03b20bd0026",
    "ffffb2fed976feb24cfd8d3cfc4e2ae31a1cb10026",
    "ffffccffeda0fed976feb24cfd8d3cfc4e2ae31a1cb10026",
    "ffffccffeda0fed976feb24cfd8d3cfc4e2ae31a1cbd0026800026"}},
  {"YlOrBr", RampType::kSequential,
   {"fff7bcfec44fd95f0e",
    "ffffd4fed98efe9929cc4c02",
    "ffffd4fed98efe9929d95f0e993404",
    "ffffd4fee391fec44ffe9929d95f0e993404",
    "ffffd4fee391fec44ffe9929ec7014cc4c028c2d04",
    "ffffe5fff7bcfee391fec44ffe9929ec7014cc4c028c2d04",
    "ffffe5fff7bcfee391fec44ffe9929ec7014cc4c02993404662506"}},
  {"YlGnBu", RampType::kSequential,
   {"edf8b17fcdbb2c7fb8",
    "ffffcca1dab441b6c4225ea8",
    "ffffcca1dab441b6c42c7fb8253494",
    "ffffccc7e9b47fcdbb41b6c42c7fb8253494",
    "ffffccc7e9b47fcdbb41b6c41d91c0225ea80c2c84",
    "ffffd9edf8b1c7e9b47fcdbb41b6c41d91c0225ea80c2c84",
    "ffffd9edf8b1c7e9b47fcdbb41b6c41d91c0225ea8253494081d58"}},
  {"YlGn", RampType::kSequential,
   {"f7fcb9addd8e31a354",
    "ffffccc2e69978c679238443",
    "ffffccc2e69978c67931a354006837",
    "ffffccd9f0a3addd8e78c67931a354006837",
    "ffffccd9f0a3addd8e78c67941ab5d238443005a32",
    "ffffe5f7fcb9d9f0a3addd8e78c67941ab5d238443005a32",
    "ffffe5f7fcb9d9f0a3addd8e78c67941ab5d238443006837004529"}},
  {"Reds", RampType::kSequential,
   {"fee0d2fc9272de2d26",
    "fee5d9fcae91fb6a4acb181d",
    "fee5d9fcae91fb6a4ade2d26a50f15",
    "fee5d9fcbba1fc9272fb6a4ade2d26a50f15",
    "fee5d9fcbba1fc9272fb6a4aef3b2ccb181d99000d",
    "fff5f0fee0d2fcbba1fc9272fb6a4aef3b2ccb181d99000d",
    "fff5f0fee0d2fcbba1fc9272fb6a4aef3b2ccb181da50f1567000d"}},
  {"RdPu", RampType::kSequential,
   {"fde0ddfa9fb5c51b8a",
    "feebe2fbb4b9f768a1ae017e",
    "feebe2fbb4b9f768a1c51b8a7a0177",
    "feebe2fcc5c0fa9fb5f768a1c51b8a7a0177",
    "feebe2fcc5c0fa9fb5f768a1dd3497ae017e7a0177",
    "fff7f3fde0ddfcc5c0fa9fb5f768a1dd3497ae017e7a0177",
    "fff7f3fde0ddfcc5c0fa9fb5f768a1dd3497ae017e7a017749006a"}},
  {"Purples", RampType::kSequential,
   {"efedf5bcbddc756bb1",
    "f2f0f7cbc9e29e9ac86a51a3",
    "f2f0f7cbc9e29e9ac8756bb154278f",
    "f2f0f7dadaebbcbddc9e9ac8756bb154278f",
    "f2f0f7dadaebbcbddc9e9ac8807dba6a51a34a1486",
    "fcfbfdefedf5dadaebbcbddc9e9ac8807dba6a51a34a1486",
    "fcfbfdefedf5dadaebbcbddc9e9ac8807dba6a51a354278f3f007d"}},
  {"PuRd", RampType::kSequential,
   {"e7e1efc994c7dd1c77",
    "f1eef6d7b5d8df65b0ce1256",
    "f1eef6d7b5d8df65b0dd1c77980043",
    "f1eef6d4b9dac994c7df65b0dd1c77980043",
    "f1eef6d4b9dac994c7df65b0e7298ace125691003f",
    "f7f4f9e7e1efd4b9dac994c7df65b0e7298ace125691003f",
    "f7f4f9e7e1efd4b9dac994c7df65b0e7298ace125698004367001f"}},
  {"PuBuGn", RampType::kSequential,
   {"ece2f0a6bddb1c9099",
    "f6eff7bdc9e167a9cf02818a",
    "f6eff7bdc9e167a9cf1c9099016c59",
    "f6eff7d0d1e6a6bddb67a9cf1c9099016c59",
    "f6eff7d0d1e6a6bddb67a9cf3690c002818a016450",
    "fff7fbece2f0d0d1e6a6bddb67a9cf3690c002818a016450",
    "fff7fbece2f0d0d1e6a6bddb67a9cf3690c002818a016c59014636"}},
  {"PuBu", RampType::kSequential,
   {"ece7f2a6bddb2b8cbe",
    "f1eef6bdc9e174a9cf0570b0",
    "f1eef6bdc9e174a9cf2b8cbe045a8d",
    "f1eef6d0d1e6a6bddb74a9cf2b8cbe045a8d",
    "f1eef6d0d1e6a6bddb74a9cf3690c00570b0034e7b",
    "fff7fbece7f2d0d1e6a6bddb74a9cf3690c00570b0034e7b",
    "fff7fbece7f2d0d1e6a6bddb74a9cf3690c00570b0045a8d023858"}},
  {"OrRd", RampType::kSequential,
   {"fee8c8fdbb84e34a33",
    "fef0d9fdcc8afc8d59d7301f",
    "fef0d9fdcc8afc8d59e34a33b30000",
    "fef0d9fdd49efdbb84fc8d59e34a33b30000",
    "fef0d9fdd49efdbb84fc8d59ef6548d7301f990000",
    "fff7ecfee8c8fdd49efdbb84fc8d59ef6548d7301f990000",
    "fff7ecfee8c8fdd49efdbb84fc8d59ef6548d7301fb300007f0000"}},
  {"Oranges", RampType::kSequential,
   {"fee6cefdae6be6550d",
    "feeddefdbe85fd8d3cd94701",
    "feeddefdbe85fd8d3ce6550da63603",
    "feeddefdd0a2fdae6bfd8d3ce6550da63603",
    "feeddefdd0a2fdae6bfd8d3cf16913d948018c2d04",
    "fff5ebfee6cefdd0a2fdae6bfd8d3cf16913d948018c2d04",
    "fff5ebfee6cefdd0a2fdae6bfd8d3cf16913d94801a636037f2704"}},
  {"Greys", RampType::kSequential,
   {"f0f0f0bdbdbd636363",
    "f7f7f7cccccc969696525252",
    "f7f7f7cccccc969696636363252525",
    "f7f7f7d9d9d9bdbdbd969696636363252525",
    "f7f7f7d9d9d9bdbdbd969696737373525252252525",
    "fffffff0f0f0d9d9d9bdbdbd969696737373525252252525",
    "fffffff0f0f0d9d9d9bdbdbd969696737373525252252525000000"}},
  {"Greens", RampType::kSequential,
   {"e5f5e0a1d99b31a354",
    "edf8e9bae4b374c476238b45",
    "edf8e9bae4b374c47631a354006d2c",
    "edf8e9c7e9c0a1d99b74c47631a354006d2c",
    "edf8e9c7e9c0a1d99b74c47641ab5d238b45005a32",
    "f7fcf5e5f5e0c7e9c0a1d99b74c47641ab5d238b45005a32",
    "f7fcf5e5f5e0c7e9c0a1d99b74c47641ab5d238b45006d2c00441b"}},
  {"GnBu", RampType::kSequential,
   {"e0f3dba8ddb543a2ca",
    "f0f9e8bae4bc7bccc42b8cbe",
    "f0f9e8bae4bc7bccc443a2ca0868ac",
    "f0f9e8ccebc5a8ddb57bccc443a2ca0868ac",
    "f0f9e8ccebc5a8ddb57bccc44eb3d32b8cbe08589e",
    "f7fcf0e0f3dbccebc5a8ddb57bccc44eb3d32b8cbe08589e",
    "f7fcf0e0f3dbccebc5a8ddb57bccc44eb3d32b8cbe0868ac084081"}},
  {"BuPu", RampType::kSequential,
   {"e0ecf49ebcda8856a7",
    "edf8fbb3cde38c96c688419d",
    "edf8fbb3cde38c96c68856a7810f7c",
    "edf8fbbfd3e69ebcda8c96c68856a7810f7c",
    "edf8fbbfd3e69ebcda8c96c68c6bb188419d6e016b",
    "f7fcfde0ecf4bfd3e69ebcda8c96c68c6bb188419d6e016b",
    "f7fcfde0ecf4bfd3e69ebcda8c96c68c6bb188419d810f7c4d004b"}},
  {"BuGn", RampType::kSequential,
   {"e5f5f999d8c92ca25f",
    "edf8fbb2e2e266c2a4238b45",
    "edf8fbb2e2e266c2a42ca25f006d2c",
    "edf8fbccece699d8c966c2a42ca25f006d2c",
    "edf8fbccece699d8c966c2a441ae76238b45005824",
    "f7fcfde5f5f9ccece699d8c966c2a441ae76238b45005824",
    "f7fcfde5f5f9ccece699d8c966c2a441ae76238b45006d2c00441b"}},
  {"Blues", RampType::kSequential,
   {"deebf79ecae13182bd",
    "eff3ffbdd7e76baed62171b5",
    "eff3ffbdd7e76baed63182bd08519c",
    "eff3ffc6dbef9ecae16baed63182bd08519c",
    "eff3ffc6dbef9ecae16baed64292c62171b5084594",
    "f7fbffdeebf7c6dbef9ecae16baed64292c62171b5084594",
    "f7fbffdeebf7c6dbef9ecae16baed64292c62171b508519c08306b"}},
  {"Spectral", RampType::kDiverging,
   {"fc8d59ffffbf99d594",
    "d7191cfdae61abdda42b83ba",
    "d7191cfdae61ffffbfabdda42b83ba",
    "d53e4ffc8d59fee08be6f59899d5943288bd",
    "d53e4ffc8d59fee08bffffbfe6f59899d5943288bd",
    "d53e4ff46d43fdae61fee08be6f598abdda466c2a53288bd",
    "d53e4ff46d43fdae61fee08bffffbfe6f598abdda466c2a53288bd",
    "9e0142d53e4ff46d43fdae61fee08be6f598abdda466c2a53288bd5e4fa2",
    "9e0142d53e4ff46d43fdae61fee08bffffbfe6f598abdda466c2a53288bd5e4fa2"}},
  {"RdYlGn", RampType::kDiverging,
   {"fc8d59ffffbf91cf60",
    "d7191cfdae61a6d96a1a9641",
    "d7191cfdae61ffffbfa6d96a1a9641",
    "d73027fc8d59fee08bd9ef8b91cf601a9850",
    "d73027fc8d59fee08bffffbfd9ef8b91cf601a9850",
    "d73027f46d43fdae61fee08bd9ef8ba6d96a66bd631a9850",
    "d73027f46d43fdae61fee08bffffbfd9ef8ba6d96a66bd631a9850",
    "a50026d73027f46d43fdae61fee08bd9ef8ba6d96a66bd631a9850006837",
    "a50026d73027f46d43fdae61fee08bffffbfd9ef8ba6d96a66bd631a9850006837"}},
  {"RdYlBu", RampType::kDiverging,
   {"fc8d59ffffbf91bfdb",
    "d7191cfdae61abd9e92c7bb6",
    "d7191cfdae61ffffbfabd9e92c7bb6",
    "d73027fc8d59fee090e0f3f891bfdb4575b4",
    "d73027fc8d59fee090ffffbfe0f3f891bfdb4575b4",
    "d73027f46d43fdae61fee090e0f3f8abd9e974add14575b4",
    "d73027f46d43fdae61fee090ffffbfe0f3f8abd9e974add14575b4",
    "a50026d73027f46d43fdae61fee090e0f3f8abd9e974add14575b4313695",
    "a50026d73027f46d43fdae61fee090ffffbfe0f3f8abd9e974add14575b4313695"}},
  {"RdGy", RampType::kDiverging,
   {"ef8a62ffffff999999",
    "ca0020f4a582bababa404040",
    "ca0020f4a582ffffffbababa404040",
    "b2182bef8a62fddbc7e0e0e09999994d4d4d",
    "b2182bef8a62fddbc7ffffffe0e0e09999994d4d4d",
    "b2182bd6604df4a582fddbc7e0e0e0bababa8787874d4d4d",
    "b2182bd6604df4a582fddbc7ffffffe0e0e0bababa8787874d4d4d",
    "67001fb2182bd6604df4a582fddbc7e0e0e0bababa8787874d4d4d1a1a1a",
    "67001fb2182bd6604df4a582fddbc7ffffffe0e0e0bababa8787874d4d4d1a1a1a"}},
  {"RdBu", RampType::kDiverging,
   {"ef8a62f7f7f767a9cf",
    "ca0020f4a58292c5de0571b0",
    "ca0020f4a582f7f7f792c5de0571b0",
    "b2182bef8a62fddbc7d1e5f067a9cf2166ac",
    "b2182bef8a62fddbc7f7f7f7d1e5f067a9cf2166ac",
    "b2182bd6604df4a582fddbc7d1e5f092c5de4393c32166ac",
    "b2182bd6604df4a582fddbc7f7f7f7d1e5f092c5de4393c32166ac",
    "67001fb2182bd6604df4a582fddbc7d1e5f092c5de4393c32166ac053061",
    "67001fb2182bd6604df4a582fddbc7f7f7f7d1e5f092c5de4393c32166ac053061"}},
  {"PuOr", RampType::kDiverging,
   {"f1a340f7f7f7998ec3",
    "e66101fdb863b2abd25e3c99",
    "e66101fdb863f7f7f7b2abd25e3c99",
    "b35806f1a340fee0b6d8daeb998ec3542788",
    "b35806f1a340fee0b6f7f7f7d8daeb998ec3542788",
    "b35806e08214fdb863fee0b6d8daebb2abd28073ac542788",
    "b35806e08214fdb863fee0b6f7f7f7d8daebb2abd28073ac542788",
    "7f3b08b35806e08214fdb863fee0b6d8daebb2abd28073ac5427882d004b",
    "7f3b08b35806e08214fdb863fee0b6f7f7f7d8daebb2abd28073ac5427882d004b"}},
  {"PRGn", RampType::kDiverging,
   {"af8dc3f7f7f77fbf7b",
    "7b3294c2a5cfa6dba0008837",
    "7b3294c2a5cff7f7f7a6dba0008837",
    "762a83af8dc3e7d4e8d9f0d37fbf7b1b7837",
    "762a83af8dc3e7d4e8f7f7f7d9f0d37fbf7b1b7837",
    "762a839970abc2a5cfe7d4e8d9f0d3a6dba05aae611b7837",
    "762a839970abc2a5cfe7d4e8f7f7f7d9f0d3a6dba05aae611b7837",
    "40004b762a839970abc2a5cfe7d4e8d9f0d3a6dba05aae611b783700441b",
    "40004b762a839970abc2a5cfe7d4e8f7f7f7d9f0d3a6dba05aae611b783700441b"}},
  {"PiYG", RampType::kDiverging,
   {"e9a3c9f7f7f7a1d76a",
    "d01c8bf1b6dab8e1864dac26",
    "d01c8bf1b6daf7f7f7b8e1864dac26",
    "c51b7de9a3c9fde0efe6f5d0a1d76a4d9221",
    "c51b7de9a3c9fde0eff7f7f7e6f5d0a1d76a4d9221",
    "c51b7dde77aef1b6dafde0efe6f5d0b8e1867fbc414d9221",
    "c51b7dde77aef1b6dafde0eff7f7f7e6f5d0b8e1867fbc414d9221",
    "8e0152c51b7dde77aef1b6dafde0efe6f5d0b8e1867fbc414d9221276419",
    "8e0152c51b7dde77aef1b6dafde0eff7f7f7e6f5d0b8e1867fbc414d9221276419"}},
  {"BrBG", RampType::kDiverging,
   {"d8b365f5f5f55ab4ac",
    "a6611adfc27d80cdc1018571",
    "a6611adfc27df5f5f580cdc1018571",
    "8c510ad8b365f6e8c3c7eae55ab4ac01665e",
    "8c510ad8b365f6e8c3f5f5f5c7eae55ab4ac01665e",
    "8c510abf812ddfc27df6e8c3c7eae580cdc135978f01665e",
    "8c510abf812ddfc27df6e8c3f5f5f5c7eae580cdc135978f01665e",
    "5430058c510abf812ddfc27df6e8c3c7eae580cdc135978f01665e003c30",
    "5430058c510abf812ddfc27df6e8c3f5f5f5c7eae580cdc135978f01665e003c30"}},
};
// clang-format on

constexpr std::size_t kRampCount = sizeof(kRamps) / sizeof(kRamps[0]);

int max_classes(const RampTable& r) {
  return r.type == RampType::kSequential ? 9 : 11;
}

}  // namespace

std::optional<ClassMethod> parse_class_method(std::string_view name) {
  if (name == "quantile") return ClassMethod::kQuantile;
  if (name == "equal") return ClassMethod::kEqual;
  if (name == "jenks") return ClassMethod::kJenks;
  if (name == "pretty") return ClassMethod::kPretty;
  return std::nullopt;
}

const char* class_method_name(ClassMethod m) {
  switch (m) {
    case ClassMethod::kQuantile:
      return "quantile";
    case ClassMethod::kEqual:
      return "equal";
    case ClassMethod::kJenks:
      return "jenks";
    case ClassMethod::kPretty:
      return "pretty";
  }
  return "unknown";
}

std::vector<double> class_breaks(std::span<const double> values, int classes, ClassMethod method) {
  if (classes < 2 || classes > 12) {
    throw std::invalid_argument("class_breaks: classes must be 2 to 12, not " +
                                std::to_string(classes));
  }
  const std::vector<double> x = finite_sorted(values);
  if (x.empty()) throw std::invalid_argument("class_breaks: no finite value");
  if (x.front() == x.back()) return {x.front(), x.front()};
  switch (method) {
    case ClassMethod::kQuantile:
      return monotone_unique(quantile_breaks(x, classes));
    case ClassMethod::kEqual:
      return monotone_unique(linear_breaks(x.front(), x.back(), classes));
    case ClassMethod::kJenks:
      return jenks_breaks(x, classes);  // increasing already (see the header)
    case ClassMethod::kPretty:
      return monotone_unique(pretty_breaks(x.front(), x.back(), classes));
  }
  throw std::invalid_argument("class_breaks: unknown method");
}

int class_of(double v, std::span<const double> breaks) {
  if (!std::isfinite(v) || breaks.size() < 2) return -1;
  if (!(v >= breaks.front() && v <= breaks.back())) return -1;
  const int k = static_cast<int>(breaks.size()) - 1;
  if (v == breaks.back()) return k - 1;
  const auto above = std::upper_bound(breaks.begin(), breaks.end(), v);
  return static_cast<int>(above - breaks.begin()) - 1;
}

std::span<const ColorRamp> color_ramps() {
  static const std::array<ColorRamp, kRampCount> ramps = [] {
    std::array<ColorRamp, kRampCount> r{};
    for (std::size_t i = 0; i < kRampCount; ++i) {
      r[i] = {kRamps[i].name, kRamps[i].type, 3, max_classes(kRamps[i])};
    }
    return r;
  }();
  return ramps;
}

std::optional<std::vector<std::string>> ramp_colors(std::string_view name, int classes) {
  for (const RampTable& r : kRamps) {
    if (!equal_ignoring_case(name, r.name)) continue;
    if (classes < 3 || classes > max_classes(r)) return std::nullopt;
    const std::string_view hex = r.colours[classes - 3];
    std::vector<std::string> out;
    for (int i = 0; i < classes; ++i)
      out.push_back("#" + std::string(hex.substr(6 * i, 6)));
    return out;
  }
  return std::nullopt;
}

}  // namespace globe
