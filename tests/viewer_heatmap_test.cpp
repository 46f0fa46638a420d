// Heatmaps of point packages (docs/viewer.md "Heatmaps"): the density the
// viewer draws, read back with --pick at sampled ground points, against a
// kernel sum written here from the CSV's own places (great-circle distances,
// the same quartic kernel): correlated >= 0.95 and equal in total (the
// kernel integrates to the weight over the ground). A radius in pixels
// shrinks the peak with its square.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "render_fixtures.hpp"
#include "test_support.hpp"

namespace {

using namespace globe_test;

struct Place {
  double lon, lat, w;
};

// Three clusters of places over the Alps and around, deterministic.
std::vector<Place> make_places() {
  std::vector<Place> p;
  uint64_t s = 12345;
  auto uniform = [&] {
    s = s * 6364136223846793005ull + 1442695040888963407ull;
    return double(s >> 11) / double(1ull << 53);
  };
  const double centres[3][3] = {{7.5, 45.5, 0.6}, {11.0, 47.5, 0.9}, {13.5, 45.8, 0.4}};
  for (const auto& c : centres)
    for (int i = 0; i < 120; ++i) {
      // Box-Muller: a normal cluster of c[2] degrees.
      const double r = std::sqrt(-2 * std::log(std::max(uniform(), 1e-12))),
                   a = 2 * M_PI * uniform();
      p.push_back({c[0] + c[2] * r * std::cos(a), c[1] + c[2] * r * std::sin(a),
                   1 + std::floor(uniform() * 9)});
    }
  return p;
}

// Great-circle distance in metres (mean Earth radius).
double distance_m(double lon1, double lat1, double lon2, double lat2) {
  const double d = M_PI / 180;
  const double a =
      std::pow(std::sin((lat2 - lat1) * d / 2), 2) +
      std::cos(lat1 * d) * std::cos(lat2 * d) * std::pow(std::sin((lon2 - lon1) * d / 2), 2);
  return 2 * 6371008.8 * std::asin(std::sqrt(a));
}

// The brute force: weight per km^2 at (lon, lat), quartic kernel of radius r.
double density_per_km2(const std::vector<Place>& places, double lon, double lat, double r_m) {
  double sum = 0;
  for (const Place& p : places) {
    const double q = std::pow(distance_m(lon, lat, p.lon, p.lat) / r_m, 2);
    if (q < 1) sum += p.w * 3 / (M_PI * r_m * r_m) * (1 - q) * (1 - q);
  }
  return sum * 1e6;
}

// The viewer's densities at the picked points ("heatmap: V per km2" each).
std::vector<double> picked(const std::string& out) {
  std::vector<double> v;
  std::istringstream in(out);
  std::string line;
  while (std::getline(in, line)) {
    const auto at = line.find("heatmap: ");
    if (at != std::string::npos) v.push_back(std::stod(line.substr(at + 9)));
  }
  return v;
}

class Heatmap : public ::testing::Test {
 protected:
  void SetUp() override {
    places_ = make_places();
    std::ofstream csv(dir_ / "places.csv");
    csv << "lon,lat,w\n";
    csv.precision(10);
    for (const Place& p : places_)
      csv << p.lon << "," << p.lat << "," << p.w << "\n";
    csv.close();
    pkg_ = (dir_ / "places.mbtiles").string();
    ASSERT_TRUE(run_all({vectorize() + " points -q " + (dir_ / "places.csv").string() +
                         " --xy lon,lat --fields w --merge-px 0 -o " + pkg_},
                        dir_.path()));
  }
  RunResult view(const std::string& args) {
    return run(viewer() + " --platform osmesa --size 480x270 " + pkg_ + " " + args, dir_.path());
  }
  TempDir dir_;
  std::vector<Place> places_;
  std::string pkg_;
};

TEST_F(Heatmap, DensityMatchesABruteForceKernelSum) {
  const double radius_m = 60000;
  std::string picks;
  std::vector<std::pair<double, double>> at;
  for (double lat = 44.0; lat <= 49.01; lat += 0.5)
    for (double lon = 5.0; lon <= 16.01; lon += 0.5) {
      at.push_back({lon, lat});
      picks += " --pick @" + std::to_string(lon) + "," + std::to_string(lat);
    }
  const std::string png = (dir_ / "h.png").string();
  const RunResult r = view(
      "--heatmap w --heatmap-radius 60km --flat --camera=10.5,46.5,900000,0,0"
      " --snapshot " +
      png + picks);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::vector<double> ours = picked(r.out);
  ASSERT_EQ(ours.size(), at.size()) << r.out;
  std::vector<double> ref;
  for (const auto& [lon, lat] : at)
    ref.push_back(density_per_km2(places_, lon, lat, radius_m));
  // Pearson correlation, and the ratio where the density is substantial.
  const double n = double(ours.size());
  double ma = 0, mb = 0;
  for (size_t i = 0; i < ours.size(); ++i)
    ma += ours[i] / n, mb += ref[i] / n;
  double sab = 0, saa = 0, sbb = 0, peak = 0;
  for (size_t i = 0; i < ours.size(); ++i) {
    sab += (ours[i] - ma) * (ref[i] - mb);
    saa += (ours[i] - ma) * (ours[i] - ma);
    sbb += (ref[i] - mb) * (ref[i] - mb);
    peak = std::max(peak, ref[i]);
  }
  const double corr = sab / std::sqrt(saa * sbb);
  std::vector<double> ratios;
  for (size_t i = 0; i < ours.size(); ++i)
    if (ref[i] > 0.2 * peak) ratios.push_back(ours[i] / ref[i]);
  std::sort(ratios.begin(), ratios.end());
  ASSERT_FALSE(ratios.empty());
  const double median = ratios[ratios.size() / 2];
  std::printf("heatmap: %zu points, correlation %.4f, median ratio %.3f (peak %.4g per km2)\n",
              at.size(), corr, median, peak);
  EXPECT_GE(corr, 0.95);
  EXPECT_NEAR(median, 1.0, 0.1) << "the kernel integrates to the weight over the ground";
  // The picture shows it: the ramp's oranges and reds over the clusters.
  int w = 0, h = 0;
  const auto rgb = read_rgb(png, w, h);
  size_t warm = 0;
  for (size_t i = 0; i + 2 < rgb.size(); i += 3)
    warm += rgb[i] > rgb[i + 2] + 60 && rgb[i] > rgb[i + 1] + 30;
  EXPECT_GT(warm, size_t(w) * h / 100) << "no dense colours drawn";
}

TEST_F(Heatmap, APixelRadiusShrinksThePeakWithItsSquare) {
  auto peak = [&](const char* radius) {
    const RunResult r = view(std::string("--heatmap count --heatmap-radius ") + radius +
                             " --flat --camera=11,47.5,1800000,0,0 --pick @11,47.5");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    const std::vector<double> v = picked(r.out);
    return v.empty() ? 0.0 : v[0];
  };
  const double narrow = peak("15px"), wide = peak("30px");
  std::printf("count density at the cluster: %.4g (15 px), %.4g (30 px)\n", narrow, wide);
  ASSERT_GT(wide, 0);
  // Not exactly 4: a wider kernel also gathers more of the cluster.
  EXPECT_GT(narrow / wide, 1.5);
  EXPECT_LT(narrow / wide, 4.5);
}

TEST_F(Heatmap, BadOptionsAreClearErrors) {
  const std::string snap = " --snapshot " + (dir_ / "x.png").string();
  RunResult r = view("--heatmap height" + snap);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("--heatmap height: "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("has no such field (w; or count)"), std::string::npos) << r.err;
  r = view("--heatmap count --heatmap-radius -3px" + snap);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("--heatmap-radius"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "x.png"));
}

}  // namespace
