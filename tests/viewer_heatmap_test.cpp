// Heatmaps of point packages (docs/viewer.md "Heatmaps"): the density the
// viewer draws, read back with --pick at sampled ground points, against a
// kernel sum written here from the CSV's own places (great-circle distances,
// the same quartic kernel): correlated >= 0.95 and equal in total (the
// kernel integrates to the weight over the ground). A radius in pixels
// shrinks the peak with its square. Heatmaps of line packages likewise,
// against an integral along the GeoJSON's own lines.
#include <gtest/gtest.h>

#include <algorithm>
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

struct Cluster {
  double lon, lat, sigma_deg;  // a normal cluster (sigma in degrees of latitude)
};

// 120 places around each cluster centre, deterministic; longitudes wrapped
// to -180..180, east-west spreads widened by 1 / cos(latitude) so clusters
// are round on the ground.
std::vector<Place> make_places(const std::vector<Cluster>& clusters) {
  std::vector<Place> p;
  uint64_t s = 12345;
  auto uniform = [&] {
    s = s * 6364136223846793005ull + 1442695040888963407ull;
    return double(s >> 11) / double(1ull << 53);
  };
  for (const Cluster& c : clusters)
    for (int i = 0; i < 120; ++i) {
      // Box-Muller.
      const double r = std::sqrt(-2 * std::log(std::max(uniform(), 1e-12))),
                   a = 2 * M_PI * uniform();
      double lon = c.lon + c.sigma_deg * r * std::cos(a) / std::cos(c.lat * M_PI / 180);
      lon = lon > 180 ? lon - 360 : lon < -180 ? lon + 360 : lon;
      p.push_back({lon, c.lat + c.sigma_deg * r * std::sin(a), 1 + std::floor(uniform() * 9)});
    }
  return p;
}

// Three clusters of places over the Alps and around.
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

// --pick options at every half degree of lon0..lon1 x lat0..lat1; `at`
// gets the points.
std::string pick_grid(double lon0, double lon1, double lat0, double lat1,
                      std::vector<std::pair<double, double>>& at) {
  std::string picks;
  for (double lat = lat0; lat <= lat1 + 0.01; lat += 0.5)
    for (double lon = lon0; lon <= lon1 + 0.01; lon += 0.5) {
      at.push_back({lon, lat});
      picks += " --pick @" + std::to_string(lon) + "," + std::to_string(lat);
    }
  return picks;
}

// Pearson correlation of two samples.
double correlation(const std::vector<double>& a, const std::vector<double>& b) {
  const double n = double(a.size());
  double ma = 0, mb = 0;
  for (size_t i = 0; i < a.size(); ++i)
    ma += a[i] / n, mb += b[i] / n;
  double sab = 0, saa = 0, sbb = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    sab += (a[i] - ma) * (b[i] - mb);
    saa += (a[i] - ma) * (a[i] - ma);
    sbb += (b[i] - mb) * (b[i] - mb);
  }
  return sab / std::sqrt(saa * sbb);
}

// The median of ours / reference where the reference is over a fifth of its
// peak (0 when there is none).
double median_ratio(const std::vector<double>& ours, const std::vector<double>& ref) {
  const double peak = *std::max_element(ref.begin(), ref.end());
  std::vector<double> ratios;
  for (size_t i = 0; i < ours.size(); ++i)
    if (ref[i] > 0.2 * peak) ratios.push_back(ours[i] / ref[i]);
  std::sort(ratios.begin(), ratios.end());
  return ratios.empty() ? 0 : ratios[ratios.size() / 2];
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
  std::vector<std::pair<double, double>> at;
  const std::string picks = pick_grid(5.0, 16.0, 44.0, 49.0, at);
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
  const double corr = correlation(ours, ref), median = median_ratio(ours, ref);
  const double peak = *std::max_element(ref.begin(), ref.end());
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

// --heatmap-colormap: the density in a colour file's colours (percentages of
// the largest density), here all blue, transparent where there is none.
TEST_F(Heatmap, AColourFileColoursTheDensity) {
  std::ofstream(dir_ / "blue.txt") << "0% 0 0 255 0\n1% 0 0 255 255\n100% 0 0 255 255\n";
  auto census = [&](const std::string& options) {
    const std::string png = (dir_ / "c.png").string();
    const RunResult r = view(
        "--heatmap count --heatmap-radius 60km --flat "
        "--camera=10.5,46.5,900000,0,0 --snapshot " +
        png + " " + options);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    int w = 0, h = 0;
    const auto rgb = read_rgb(png, w, h);
    size_t blue = 0, warm = 0;
    for (size_t i = 0; i + 2 < rgb.size(); i += 3) {
      blue += rgb[i + 2] > rgb[i] + 60;
      warm += rgb[i] > rgb[i + 2] + 60;
    }
    return std::pair(blue, warm);
  };
  const auto [blue, warm] = census("--heatmap-colormap " + (dir_ / "blue.txt").string());
  const auto [plain_blue, plain_warm] = census("");
  std::printf("blue file: %zu blue, %zu warm pixels; built-in: %zu blue, %zu warm\n", blue, warm,
              plain_blue, plain_warm);
  EXPECT_GT(blue, 1000u);
  EXPECT_EQ(warm, 0u);
  EXPECT_GT(plain_warm, 1000u);
  EXPECT_EQ(plain_blue, 0u);
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

// The same brute force where the plane of a map misleads: clusters across
// the antimeridian (Fiji: the kernel of a place at 179.8 E reaches ground at
// 179.6 W) and in the Arctic (Svalbard, 78-80 N, where a degree of longitude
// is a fifth of one at the equator), on the globe, and in the Arctic on the
// flat map too (the flat map frame ends at 180 degrees: it draws no copy of
// the world east of it, docs/viewer.md "Not yet").
struct Region {
  const char* name;
  std::vector<Cluster> clusters;
  double lon0, lon1, lat0, lat1;  // the picked grid (lon1 may pass 180)
  const char* camera;             // --flat or not, --camera
};

void PrintTo(const Region& r, std::ostream* os) {
  *os << r.name;
}

class HeatmapAtTheEdges : public ::testing::TestWithParam<Region> {};

TEST_P(HeatmapAtTheEdges, DensityMatchesABruteForceKernelSum) {
  const Region& region = GetParam();
  TempDir dir;
  const std::vector<Place> places = make_places(region.clusters);
  {
    std::ofstream csv(dir / "places.csv");
    csv << "lon,lat,w\n";
    csv.precision(10);
    for (const Place& p : places)
      csv << p.lon << "," << p.lat << "," << p.w << "\n";
  }
  const std::string pkg = (dir / "places.mbtiles").string();
  ASSERT_TRUE(run_all({vectorize() + " points -q " + (dir / "places.csv").string() +
                       " --xy lon,lat --fields w --merge-px 0 -o " + pkg},
                      dir.path()));
  std::vector<std::pair<double, double>> at;
  std::string picks;
  for (double lat = region.lat0; lat <= region.lat1 + 0.01; lat += 0.5)
    for (double lon = region.lon0; lon <= region.lon1 + 0.01; lon += 0.5) {
      const double wrapped = lon > 180 ? lon - 360 : lon;
      at.push_back({wrapped, lat});
      picks += " --pick @" + std::to_string(wrapped) + "," + std::to_string(lat);
    }
  const RunResult r = run(viewer() + " --platform osmesa --size 480x270 " + pkg +
                              " --heatmap w --heatmap-radius 60km " + region.camera + picks,
                          dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::vector<double> ours = picked(r.out);
  ASSERT_EQ(ours.size(), at.size()) << r.out;
  std::vector<double> ref;
  for (const auto& [lon, lat] : at)
    ref.push_back(density_per_km2(places, lon, lat, 60000));
  const double corr = correlation(ours, ref), median = median_ratio(ours, ref);
  size_t east = 0, west = 0;  // dense points on either side of the antimeridian
  const double peak = *std::max_element(ref.begin(), ref.end());
  for (size_t i = 0; i < at.size(); ++i)
    if (ref[i] > 0.2 * peak) (at[i].first < 0 ? west : east) += 1;
  std::printf(
      "%s: %zu points (%zu dense east of 0, %zu west), correlation %.4f, median ratio %.3f\n",
      region.name, at.size(), east, west, corr, median);
  EXPECT_GE(corr, 0.95);
  EXPECT_NEAR(median, 1.0, 0.1);
}

INSTANTIATE_TEST_SUITE_P(Regions, HeatmapAtTheEdges,
                         ::testing::Values(Region{"antimeridian_globe",
                                                  {{179.6, -17.5, 0.5}, {-179.5, -16.2, 0.4}},
                                                  176.5,
                                                  183.5,
                                                  -20,
                                                  -14,
                                                  "--camera=180,-17,1200000,0,0"},
                                           Region{"arctic_flat",
                                                  {{16.0, 78.3, 0.4}, {25.0, 79.4, 0.35}},
                                                  10,
                                                  31,
                                                  76.5,
                                                  81,
                                                  "--flat --camera=20.5,78.8,900000,0,0"},
                                           Region{"arctic_globe",
                                                  {{16.0, 78.3, 0.4}, {25.0, 79.4, 0.35}},
                                                  10,
                                                  31,
                                                  76.5,
                                                  81,
                                                  "--camera=20.5,78.8,1200000,0,0"}),
                         [](const auto& info) { return std::string(info.param.name); });

// A heatmap of a line package: the density of the lines' length (weight 1
// per metre), against a kernel sum along the GeoJSON's own lines written
// here (great-circle lengths and distances, 100 m steps).
TEST(HeatmapOfLines, DensityMatchesABruteForceIntegralAlongTheLines) {
  TempDir dir;
  // Two crossing lines and a ring, densified (0.05 degrees) so that straight
  // in webmercator and straight in lon/lat agree.
  std::vector<std::vector<std::pair<double, double>>> lines(3);
  for (int i = 0; i <= 180; ++i) {
    const double t = i / 180.0;
    lines[0].push_back({6 + 9 * t, 44 + 5 * t});
    lines[1].push_back({6 + 9 * t, 48 - 3 * t});
    const double a = 2 * M_PI * t;
    lines[2].push_back({11 + 1.2 * std::cos(a), 46.5 + 0.8 * std::sin(a)});
  }
  {
    std::ofstream f(dir / "l.geojson");
    f.precision(10);
    f << R"({"type":"FeatureCollection","features":[)";
    for (size_t l = 0; l < lines.size(); ++l) {
      f << (l ? "," : "") << R"({"type":"Feature","properties":{},"geometry":{"type":)"
        << R"("LineString","coordinates":[)";
      for (size_t k = 0; k < lines[l].size(); ++k)
        f << (k ? "," : "") << "[" << lines[l][k].first << "," << lines[l][k].second << "]";
      f << "]}}";
    }
    f << "]}\n";
  }
  const std::string pkg = (dir / "l.mbtiles").string();
  ASSERT_TRUE(run_all({vectorize() + " lines -q " + (dir / "l.geojson").string() + " -o " + pkg},
                      dir.path()));
  const double radius_m = 60000;
  std::vector<std::pair<double, double>> at;
  const std::string picks = pick_grid(5.5, 15.5, 44.0, 49.0, at);
  const RunResult r = run(viewer() + " --platform osmesa --size 480x270 " + pkg +
                              " --heatmap count --heatmap-radius 60km --flat"
                              " --camera=10.5,46.5,900000,0,0 --snapshot " +
                              (dir / "h.png").string() + picks,
                          dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::vector<double> ours = picked(r.out);
  ASSERT_EQ(ours.size(), at.size()) << r.out;
  // The brute force: km of line per km^2, the quartic kernel along each line.
  std::vector<double> ref;
  for (const auto& [lon, lat] : at) {
    double sum = 0;
    for (const auto& l : lines)
      for (size_t k = 0; k + 1 < l.size(); ++k) {
        const double len = distance_m(l[k].first, l[k].second, l[k + 1].first, l[k + 1].second);
        const int n = std::max(1, int(std::ceil(len / 100)));
        for (int i = 0; i < n; ++i) {
          const double t = (i + 0.5) / n;
          const double q =
              std::pow(distance_m(lon, lat, l[k].first + t * (l[k + 1].first - l[k].first),
                                  l[k].second + t * (l[k + 1].second - l[k].second)) /
                           radius_m,
                       2);
          if (q < 1) sum += len / n * 3 / (M_PI * radius_m * radius_m) * (1 - q) * (1 - q);
        }
      }
    ref.push_back(sum * 1e3);  // m per m^2 -> km per km^2
  }
  const double corr = correlation(ours, ref), median = median_ratio(ours, ref);
  std::printf("line heatmap: %zu points, correlation %.4f, median ratio %.3f\n", at.size(), corr,
              median);
  EXPECT_GE(corr, 0.95);
  EXPECT_NEAR(median, 1.0, 0.1) << "the kernel integrates to the line's length over the ground";
}

}  // namespace
