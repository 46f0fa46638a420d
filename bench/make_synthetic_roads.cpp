// Writes a synthetic road network and flows over it for the bundling
// benchmark (bench/bundle.sh), at the scale of the thesis's Table 5.1 road
// case (975,491 vertices, 31,608 connections):
//   ROADS.fgb:  a jittered grid of junctions over 5 x 4 degrees of central
//               Europe, each joined to its east and south neighbours by a
//               winding road of several vertices (and a few diagonal
//               shortcuts), so most vertices lie on chains between junctions
//               as on real roads (EPSG:4326, FlatGeobuf);
//   FLOWS.csv:  CONNECTIONS distinct town pairs (olon, olat, dlon, dlat,
//               trips), towns a few hundred metres off random junctions,
//               pairs drawn by a gravity model (nearer towns more often),
//               trips from a heavy-tailed distribution.
// Deterministic (fixed seeds). Usage:
//   make_synthetic_roads VERTICES CONNECTIONS TOWNS ROADS.fgb FLOWS.csv
#include <gdal.h>
#include <ogr_api.h>
#include <ogr_srs_api.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <set>
#include <utility>
#include <vector>

namespace {

constexpr double kWest = 5, kSouth = 45, kWidth = 5, kHeight = 4;
constexpr int kVerticesPerRoad = 6;  // interior vertices of a grid road

struct P {
  double lon, lat;
};

}  // namespace

int main(int argc, char** argv) {
  if (argc != 6) {
    std::fprintf(stderr,
                 "usage: make_synthetic_roads VERTICES CONNECTIONS TOWNS ROADS.fgb FLOWS.csv\n");
    return 2;
  }
  const long target = std::atol(argv[1]);
  const long connections = std::atol(argv[2]);
  const long towns = std::atol(argv[3]);
  if (target < 1000 || connections < 1 || towns < 2 ||
      double(connections) > 0.5 * double(towns) * double(towns - 1)) {
    std::fprintf(stderr,
                 "make_synthetic_roads: VERTICES >= 1000, TOWNS >= 2, CONNECTIONS >= 1 "
                 "and at most half of all town pairs\n");
    return 2;
  }
  // Grid side n: n^2 junctions, ~2 n^2 roads of kVerticesPerRoad + 2
  // vertices and n^2 / 8 diagonals of 2 more.
  const double per_junction = 2.0 * (kVerticesPerRoad + 2) + (kVerticesPerRoad + 4) / 8.0;
  const int n =
      std::max(4, static_cast<int>(std::lround(std::sqrt(double(target) / per_junction))));
  const double dx = kWidth / (n - 1), dy = kHeight / (n - 1);
  std::mt19937_64 rng(1975491);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<P> junction(size_t(n) * n);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      junction[size_t(j) * n + i] = {kWest + i * dx + 0.3 * dx * u(rng),
                                     kSouth + j * dy + 0.3 * dy * u(rng)};

  GDALAllRegister();
  GDALDriverH driver = GDALGetDriverByName("FlatGeobuf");
  GDALDatasetH ds = driver ? GDALCreate(driver, argv[4], 0, 0, 0, GDT_Unknown, nullptr) : nullptr;
  if (!ds) {
    std::fprintf(stderr, "make_synthetic_roads: cannot create %s\n", argv[4]);
    return 1;
  }
  OGRSpatialReferenceH srs = OSRNewSpatialReference(nullptr);
  OSRImportFromEPSG(srs, 4326);
  OGRLayerH layer = GDALDatasetCreateLayer(ds, "roads", srs, wkbLineString, nullptr);
  OSRRelease(srs);
  long vertices = 0, roads = 0;
  auto road = [&](P a, P b, int interior) {
    OGRFeatureH f = OGR_F_Create(OGR_L_GetLayerDefn(layer));
    OGRGeometryH g = OGR_G_CreateGeometry(wkbLineString);
    OGR_G_AddPoint_2D(g, a.lon, a.lat);
    // A winding road: a sine bend plus jitter across the straight line.
    const double nx = -(b.lat - a.lat), ny = b.lon - a.lon;
    const double bend = 0.08 * u(rng), wiggle = 0.02;
    for (int k = 1; k <= interior; ++k) {
      const double t = double(k) / (interior + 1);
      const double off = bend * std::sin(t * 3.14159265) + wiggle * u(rng);
      OGR_G_AddPoint_2D(g, a.lon + t * (b.lon - a.lon) + off * nx,
                        a.lat + t * (b.lat - a.lat) + off * ny);
    }
    OGR_G_AddPoint_2D(g, b.lon, b.lat);
    OGR_F_SetGeometryDirectly(f, g);
    if (OGR_L_CreateFeature(layer, f) != OGRERR_NONE) {
      std::fprintf(stderr, "make_synthetic_roads: cannot write %s\n", argv[4]);
      std::exit(1);
    }
    OGR_F_Destroy(f);
    vertices += interior + 2;
    ++roads;
  };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const P a = junction[size_t(j) * n + i];
      if (i + 1 < n) road(a, junction[size_t(j) * n + i + 1], kVerticesPerRoad);
      if (j + 1 < n) road(a, junction[size_t(j + 1) * n + i], kVerticesPerRoad);
      if (i + 1 < n && j + 1 < n && rng() % 8 == 0)  // a diagonal shortcut
        road(a, junction[size_t(j + 1) * n + i + 1], kVerticesPerRoad + 2);
    }
  GDALClose(ds);

  // Towns: a few hundred metres off distinct junctions.
  std::vector<P> town;
  std::set<size_t> used;
  while (long(town.size()) < towns && used.size() < junction.size()) {
    const size_t k = rng() % junction.size();
    if (!used.insert(k).second) continue;
    town.push_back({junction[k].lon + 0.003 * u(rng), junction[k].lat + 0.003 * u(rng)});
  }
  // Gravity model: a random origin, destinations by 1 / (distance + 10 km)^2,
  // drawn by rejection; distinct unordered pairs.
  std::FILE* csv = std::fopen(argv[5], "w");
  if (!csv) {
    std::fprintf(stderr, "make_synthetic_roads: cannot create %s\n", argv[5]);
    return 1;
  }
  std::fprintf(csv, "olon,olat,dlon,dlat,trips\n");
  std::set<std::pair<size_t, size_t>> pairs;
  std::uniform_real_distribution<double> unit(0, 1);
  while (long(pairs.size()) < connections) {
    const size_t a = rng() % town.size(), b = rng() % town.size();
    if (a == b || pairs.count({std::min(a, b), std::max(a, b)})) continue;
    const double km =
        std::hypot((town[a].lon - town[b].lon) * 71, (town[a].lat - town[b].lat) * 111);
    if (unit(rng) > std::pow(30.0 / (km + 30.0), 1.5)) continue;
    pairs.insert({std::min(a, b), std::max(a, b)});
    const int trips = 1 + static_cast<int>(std::floor(std::pow(unit(rng), -1.2)));  // heavy tail
    std::fprintf(csv, "%.6f,%.6f,%.6f,%.6f,%d\n", town[a].lon, town[a].lat, town[b].lon,
                 town[b].lat, std::min(trips, 100000));
  }
  std::fclose(csv);
  std::fprintf(stderr,
               "make_synthetic_roads: %ld roads, %ld vertices, %d x %d junctions, %zu towns, "
               "%ld connections\n",
               roads, vertices, n, n, town.size(), connections);
  return 0;
}
