// globe-view's area packages (docs/areas.md, docs/viewer.md) as a user runs
// them, checked against the SOURCE polygons read with OGR, never against the
// tools' own code: a grid of `--pick X,Y --pick-format json` per view gives
// each pixel's ground lon/lat and the area filled there, which must be the
// source feature containing that ground point (world.gpkg in both global
// tilings, from orbit, obliquely, across the antimeridian and over the South
// Pole; nc.gpkg in a local UTM tiling), away from the borders by 1.5 px;
// neighbouring counties leave no unfilled pixel between them at any zoom;
// a choropleth's pixels have their class's ColorBrewer colour (classes
// computed here as R's quantile type 7); areas over an etopo20 terrain of
// another tiling; one expected image.
//
// Distances to borders are measured on the sphere (great-circle arcs of the
// source's rings, densified in the source CRS so that a straight source
// segment is followed as the source means it) against 1.5 px, the pixel's
// size taken from its neighbouring picks' ground points.
#include <gtest/gtest.h>

#include <gdal.h>
#include <ogr_api.h>
#include <ogr_srs_api.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <numbers>
#include <sstream>

#include "raster_fixtures.hpp"
#include "render_fixtures.hpp"
#include "test_paths.hpp"
#include "test_support.hpp"
#include "tileformat/json.hpp"

namespace {

using namespace globe_test;
using tileformat::JsonValue;

constexpr double kEarthRadius = 6371008.8;  // mean sphere, metres
constexpr double kDeg = std::numbers::pi / 180;
constexpr double kMercatorLimit = 85.0511287798;  // webmercator packages stop here

// Packages built once per build tree (shared_folder), read by every test.
struct Packages {
  fs::path dir;
  std::string world_mercator, world_geodetic, world_choropleth, nc_utm, nc_local, nc_mercator,
      nc_choropleth, etopo;
};

const Packages& packages() {
  static const Packages p = [] {
    Packages k;
    k.dir = shared_folder("globe-view-areas", [](const fs::path& dir) {
      auto at = [&](const char* name) { return (dir / name).string(); };
      const std::string world = sample("world.gpkg").string(), nc = sample("nc.gpkg").string();
      const std::string areas = vectorize() + " areas -q ";
      return run_all(
          {// Finer zooms than the defaults (3 and 2), so that the package's
           // last grid is well below the pixels of the closest views.
           areas + "--max-zoom 5 " + world + " -o " + at("world_webmercator.mbtiles"),
           areas + "--tiling geodetic --max-zoom 4 " + world + " -o " +
               at("world_geodetic.mbtiles"),
           areas + world +
               " --choropleth pop/area_km2 --classes 5 --method quantile --colors YlOrRd -o " +
               at("world_choropleth.mbtiles"),
           // nc.gpkg (NAD27 lon/lat) reprojected to UTM 17N: the source of
           // a package in its own local tiling.
           "ogr2ogr -t_srs EPSG:32617 " + at("nc_utm.gpkg") + " " + nc,
           areas + "--tiling local " + at("nc_utm.gpkg") + " -o " + at("nc_local.mbtiles"),
           areas + nc + " -o " + at("nc_webmercator.mbtiles"),
           areas + nc +
               " --choropleth SID74/BIR74 --classes 5 --method quantile --colors YlOrRd -o " +
               at("nc_choropleth.mbtiles"),
           tiler() + " terrain -q --tiling geodetic " + sample("etopo20.tif").string() + " -o " +
               at("etopo_geodetic.mbtiles")},
          dir);
    });
    k.world_mercator = (k.dir / "world_webmercator.mbtiles").string();
    k.world_geodetic = (k.dir / "world_geodetic.mbtiles").string();
    k.world_choropleth = (k.dir / "world_choropleth.mbtiles").string();
    k.nc_utm = (k.dir / "nc_utm.gpkg").string();
    k.nc_local = (k.dir / "nc_local.mbtiles").string();
    k.nc_mercator = (k.dir / "nc_webmercator.mbtiles").string();
    k.nc_choropleth = (k.dir / "nc_choropleth.mbtiles").string();
    k.etopo = (k.dir / "etopo_geodetic.mbtiles").string();
    return k;
  }();
  return p;
}

// ---------------------------------------------------------------------------
// Picks

struct Pick {
  int x = 0, y = 0;
  bool ground = false;  // lon/lat not null
  double lon = 0, lat = 0, height = 0;
  bool area = false;  // "area" not null
  std::string name;   // the area's name attribute
};

// Picks on a regular grid (every `step` px from `origin`, row-major): `cols`
// by `rows` of them.
struct PickGrid {
  int cols = 0, rows = 0, step = 0, origin = 0;
  std::vector<Pick> picks;
  const Pick* at(int c, int r) const {
    if (c < 0 || r < 0 || c >= cols || r >= rows) return nullptr;
    return &picks[size_t(r) * cols + c];
  }
  // The ground size of a pixel at grid cell (c, r), metres: the largest
  // distance to a 4-neighbour's ground point over the grid step; 0 when no
  // neighbour shows ground.
  double pixel_m(int c, int r) const {
    const Pick* p = at(c, r);
    double m = 0;
    for (const auto& [dc, dr] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
      const Pick* q = at(c + dc, r + dr);
      if (q && q->ground) m = std::max(m, haversine_m(p->lon, p->lat, q->lon, q->lat) / step);
    }
    return m;
  }
};

// Runs globe-view with `args` (packages and camera) at w x h with a grid of
// picks every `step` px from `origin` (default step / 2); the area's name is
// its attribute `name_field`.
PickGrid pick_grid(const std::string& args, int w, int h, int step, const std::string& name_field,
                   const fs::path& dir, int origin = -1) {
  PickGrid g;
  g.step = step;
  g.origin = origin < 0 ? step / 2 : origin;
  g.cols = (w - g.origin + step - 1) / step;
  g.rows = (h - g.origin + step - 1) / step;
  std::string picks;
  for (int r = 0; r < g.rows; ++r)
    for (int c = 0; c < g.cols; ++c)
      picks += " --pick " + std::to_string(g.origin + c * step) + "," +
               std::to_string(g.origin + r * step);
  const RunResult res = run(viewer() + " " + args + " --size " + std::to_string(w) + "x" +
                                std::to_string(h) + " --pick-format json" + picks,
                            dir);
  EXPECT_EQ(res.exit_code, 0) << args << "\n" << res.err;
  std::istringstream lines(res.out);
  std::string line;
  while (std::getline(lines, line)) {
    if (line.empty()) continue;
    const JsonValue j = JsonValue::parse(line);
    Pick p;
    p.x = int(j.find("x")->number());
    p.y = int(j.find("y")->number());
    const JsonValue* lon = j.find("lon");
    const JsonValue* lat = j.find("lat");
    p.ground = lon && lat && !lon->is_null() && !lat->is_null();
    if (p.ground) {
      p.lon = lon->number();
      p.lat = lat->number();
      const JsonValue* height = j.find("height");
      p.height = height && !height->is_null() ? height->number() : 0;
      // One turn back into -180..180 (a ground point across the antimeridian).
      p.lon = std::remainder(p.lon, 360.0);
    }
    const JsonValue* area = j.find("area");
    p.area = area && !area->is_null();
    if (p.area) {
      const JsonValue* attrs = area->find("attributes");
      const JsonValue* name = attrs ? attrs->find(name_field) : nullptr;
      p.name = name && name->is_string() ? name->string() : "(no " + name_field + ")";
    }
    g.picks.push_back(p);
  }
  EXPECT_EQ(g.picks.size(), size_t(g.cols) * g.rows) << "one line per pick expected";
  if (g.picks.size() != size_t(g.cols) * g.rows) g.picks.clear(), g.cols = g.rows = 0;
  for (size_t i = 0; i < g.picks.size(); ++i)
    EXPECT_TRUE(g.picks[i].x == g.origin + int(i % g.cols) * step &&
                g.picks[i].y == g.origin + int(i / g.cols) * step)
        << "pick " << i << " answered for " << g.picks[i].x << "," << g.picks[i].y;
  return g;
}

// ---------------------------------------------------------------------------
// The source, read with OGR

struct Vec3 {
  double x, y, z;
};
Vec3 operator-(Vec3 a, Vec3 b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
Vec3 operator*(double s, Vec3 a) {
  return {s * a.x, s * a.y, s * a.z};
}
double dot(Vec3 a, Vec3 b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
Vec3 cross(Vec3 a, Vec3 b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
double norm(Vec3 a) {
  return std::sqrt(dot(a, a));
}
Vec3 unit(double lon, double lat) {
  return {std::cos(lat * kDeg) * std::cos(lon * kDeg), std::cos(lat * kDeg) * std::sin(lon * kDeg),
          std::sin(lat * kDeg)};
}
double angle(Vec3 a, Vec3 b) {
  return std::atan2(norm(cross(a, b)), dot(a, b));
}
// The angle from p to the great-circle arc a-b (unit vectors).
double arc_angle(Vec3 p, Vec3 a, Vec3 b) {
  Vec3 n = cross(a, b);
  const double nn = norm(n);
  if (nn < 1e-15) return angle(p, a);
  n = (1 / nn) * n;
  const double s = dot(p, n);
  const Vec3 c = p - s * n;  // p's projection on the arc's plane
  if (dot(cross(a, c), n) >= 0 && dot(cross(c, b), n) >= 0)
    return std::asin(std::min(1.0, std::abs(s)));
  return std::min(angle(p, a), angle(p, b));
}

OGRSpatialReferenceH lonlat_srs() {
  OGRSpatialReferenceH s = OSRNewSpatialReference(nullptr);
  OSRImportFromEPSG(s, 4326);
  OSRSetAxisMappingStrategy(s, OAMS_TRADITIONAL_GIS_ORDER);
  return s;
}

// A vector source's features (their names and geometries in the source CRS)
// and a set of border arcs on the sphere.
class Source {
 public:
  struct Options {
    std::string name_field;
    // World maps split at the antimeridian and closed at -89.9 (world.gpkg):
    // those edges are the map's, not borders; a ground point south of
    // -89.9 is in the ring that goes round the pole (Antarctica), which
    // docs/areas.md says the tool closes through the pole.
    bool map_edges = false;
    // Borders: only the exterior rings of the union of all features.
    bool outer_boundary_only = false;
  };

  Source(const std::string& path, Options o) : o_(std::move(o)) {
    gdal_setup();
    GDALDatasetH ds =
        GDALOpenEx(path.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY, nullptr, nullptr, nullptr);
    if (!ds) {
      ADD_FAILURE() << "OGR cannot open " << path;
      return;
    }
    OGRLayerH layer = GDALDatasetGetLayer(ds, 0);
    OGRSpatialReferenceH srs = OSRClone(OGR_L_GetSpatialRef(layer));
    OSRSetAxisMappingStrategy(srs, OAMS_TRADITIONAL_GIS_ORDER);
    geographic_ = OSRIsGeographic(srs);
    OGRSpatialReferenceH ll = lonlat_srs();
    to_source_ = OCTNewCoordinateTransformation(ll, srs);
    OGRCoordinateTransformationH to_lonlat = OCTNewCoordinateTransformation(srs, ll);
    OGR_L_ResetReading(layer);
    while (OGRFeatureH f = OGR_L_GetNextFeature(layer)) {
      OGRGeometryH g = OGR_F_GetGeometryRef(f);
      if (g) {
        Feature feature;
        feature.name = OGR_F_GetFieldAsString(f, OGR_F_GetFieldIndex(f, o_.name_field.c_str()));
        feature.geometry = OGR_G_Clone(g);
        OGR_G_GetEnvelope(feature.geometry, &feature.envelope);
        for (const char* field : {"pop", "area_km2", "SID74", "BIR74"}) {
          const int i = OGR_F_GetFieldIndex(f, field);
          if (i >= 0 && OGR_F_IsFieldSetAndNotNull(f, i))
            feature.numbers[field] = OGR_F_GetFieldAsDouble(f, i);
        }
        features_.push_back(std::move(feature));
      }
      OGR_F_Destroy(f);
    }
    // Each polygon on its own, with its envelope: a point is tested against
    // the few whose envelope holds it.
    for (size_t i = 0; i < features_.size(); ++i) {
      OGRGeometryH multi = OGR_G_CreateGeometry(wkbMultiPolygon);
      add_polygons(multi, features_[i].geometry);
      for (int j = 0; j < OGR_G_GetGeometryCount(multi); ++j) {
        Part part{int(i), OGR_G_Clone(OGR_G_GetGeometryRef(multi, j)), {}};
        OGR_G_GetEnvelope(part.polygon, &part.envelope);
        parts_.push_back(part);
      }
      OGR_G_DestroyGeometry(multi);
    }
    if (o_.outer_boundary_only) {
      OGRGeometryH all = OGR_G_CreateGeometry(wkbMultiPolygon);
      for (const Feature& f : features_)
        add_polygons(all, f.geometry);
      OGRGeometryH u = OGR_G_UnionCascaded(all);
      EXPECT_NE(u, nullptr) << "the union of " << path;
      if (u) add_outer_borders(u, to_lonlat);
      OGR_G_DestroyGeometry(u);
      OGR_G_DestroyGeometry(all);
    } else {
      for (const Feature& f : features_)
        add_borders(f.geometry, to_lonlat);
    }
    make_chunks();
    OCTDestroyCoordinateTransformation(to_lonlat);
    OSRRelease(ll);
    OSRRelease(srs);
    GDALClose(ds);
  }
  ~Source() {
    for (Feature& f : features_)
      OGR_G_DestroyGeometry(f.geometry);
    for (Part& p : parts_)
      OGR_G_DestroyGeometry(p.polygon);
    if (to_source_) OCTDestroyCoordinateTransformation(to_source_);
  }
  Source(const Source&) = delete;
  Source& operator=(const Source&) = delete;

  struct Feature {
    std::string name;
    OGRGeometryH geometry = nullptr;
    OGREnvelope envelope;
    std::map<std::string, double> numbers;
  };
  const std::vector<Feature>& features() const { return features_; }
  size_t border_arcs() const { return arcs_.size(); }

  // The feature containing lon/lat (WGS84), or -1.
  int containing(double lon, double lat) const {
    if (o_.map_edges && lat < -89.9) lat = -89.89;
    double x = lon, y = lat;
    if (!OCTTransform(to_source_, 1, &x, &y, nullptr)) return -1;
    OGRGeometryH pt = OGR_G_CreateGeometry(wkbPoint);
    OGR_G_SetPoint_2D(pt, 0, x, y);
    int found = -1;
    for (size_t i = 0; i < parts_.size() && found < 0; ++i) {
      const OGREnvelope& e = parts_[i].envelope;
      if (x < e.MinX || x > e.MaxX || y < e.MinY || y > e.MaxY) continue;
      if (OGR_G_Contains(parts_[i].polygon, pt)) found = parts_[i].feature;
    }
    OGR_G_DestroyGeometry(pt);
    return found;
  }

  // Whether a border passes within `metres` of lon/lat.
  bool near_border(double lon, double lat, double metres) const {
    const Vec3 p = unit(lon, lat);
    const double limit = metres / kEarthRadius;
    for (const Chunk& c : chunks_) {
      // angle(p, centre) > radius + limit: no arc of the chunk is near.
      if (c.radius + limit < std::numbers::pi && dot(p, c.centre) < std::cos(c.radius + limit))
        continue;
      for (size_t i = c.begin; i < c.end; ++i)
        if (arc_angle(p, arcs_[i].first, arcs_[i].second) <= limit) return true;
    }
    return false;
  }

 private:
  struct Part {
    int feature;
    OGRGeometryH polygon;
    OGREnvelope envelope;
  };
  struct Chunk {
    Vec3 centre;
    double radius;
    size_t begin, end;
  };

  static void add_polygons(OGRGeometryH multi, OGRGeometryH g) {
    const auto type = wkbFlatten(OGR_G_GetGeometryType(g));
    if (type == wkbPolygon) {
      OGR_G_AddGeometry(multi, g);
    } else {
      for (int i = 0; i < OGR_G_GetGeometryCount(g); ++i)
        add_polygons(multi, OGR_G_GetGeometryRef(g, i));
    }
  }
  void add_outer_borders(OGRGeometryH g, OGRCoordinateTransformationH to_lonlat) {
    const auto type = wkbFlatten(OGR_G_GetGeometryType(g));
    if (type == wkbPolygon) {
      if (OGR_G_GetGeometryCount(g) > 0) add_ring(OGR_G_GetGeometryRef(g, 0), to_lonlat);
    } else {
      for (int i = 0; i < OGR_G_GetGeometryCount(g); ++i)
        add_outer_borders(OGR_G_GetGeometryRef(g, i), to_lonlat);
    }
  }
  void add_borders(OGRGeometryH g, OGRCoordinateTransformationH to_lonlat) {
    if (OGR_G_GetGeometryCount(g) == 0) {
      add_ring(g, to_lonlat);
      return;
    }
    for (int i = 0; i < OGR_G_GetGeometryCount(g); ++i)
      add_borders(OGR_G_GetGeometryRef(g, i), to_lonlat);
  }
  // A ring's segments, straight in the source CRS: densified there (0.25
  // degrees, 5 km) and taken to the sphere vertex by vertex.
  void add_ring(OGRGeometryH ring, OGRCoordinateTransformationH to_lonlat) {
    const int n = OGR_G_GetPointCount(ring);
    const double step = geographic_ ? 0.25 : 5000;
    std::vector<double> xs, ys;
    for (int i = 0; i + 1 < n; ++i) {
      const double x0 = OGR_G_GetX(ring, i), y0 = OGR_G_GetY(ring, i);
      const double x1 = OGR_G_GetX(ring, i + 1), y1 = OGR_G_GetY(ring, i + 1);
      const int parts = std::max(1, int(std::ceil(std::hypot(x1 - x0, y1 - y0) / step)));
      for (int k = 0; k < parts; ++k) {
        xs.push_back(x0 + (x1 - x0) * k / parts);
        ys.push_back(y0 + (y1 - y0) * k / parts);
      }
    }
    if (n > 0) xs.push_back(OGR_G_GetX(ring, n - 1)), ys.push_back(OGR_G_GetY(ring, n - 1));
    std::vector<int> ok(xs.size());
    OCTTransformEx(to_lonlat, int(xs.size()), xs.data(), ys.data(), nullptr, ok.data());
    for (size_t i = 0; i + 1 < xs.size(); ++i) {
      if (!ok[i] || !ok[i + 1]) {
        ADD_FAILURE() << "cannot take a border vertex to lon/lat";
        continue;
      }
      if (o_.map_edges) {
        const bool antimeridian = std::abs(xs[i]) > 179.9999 && std::abs(xs[i + 1]) > 179.9999;
        const bool pole = ys[i] < -89.8999 && ys[i + 1] < -89.8999;
        if (antimeridian || pole) continue;
      }
      arcs_.emplace_back(unit(xs[i], ys[i]), unit(xs[i + 1], ys[i + 1]));
    }
    ring_ends_.push_back(arcs_.size());
  }
  // Caps around runs of up to 16 arcs of one ring: an arc lies in any cap
  // (< 90 degrees) that holds its ends.
  void make_chunks() {
    size_t ring_begin = 0;
    for (const size_t ring_end : ring_ends_) {
      for (size_t b = ring_begin; b < ring_end; b += 16)
        make_chunk(b, std::min(ring_end, b + 16));
      ring_begin = ring_end;
    }
  }
  void make_chunk(size_t begin, size_t end) {
    Chunk c{{0, 0, 0}, 0, begin, end};
    for (size_t i = begin; i < end; ++i)
      c.centre = {c.centre.x + arcs_[i].first.x + arcs_[i].second.x,
                  c.centre.y + arcs_[i].first.y + arcs_[i].second.y,
                  c.centre.z + arcs_[i].first.z + arcs_[i].second.z};
    c.centre = (1 / norm(c.centre)) * c.centre;
    for (size_t i = begin; i < end; ++i)
      c.radius =
          std::max({c.radius, angle(c.centre, arcs_[i].first), angle(c.centre, arcs_[i].second)});
    EXPECT_LT(c.radius, std::numbers::pi / 2);
    chunks_.push_back(c);
  }

  Options o_;
  bool geographic_ = false;
  OGRCoordinateTransformationH to_source_ = nullptr;
  std::vector<Feature> features_;
  std::vector<Part> parts_;
  std::vector<std::pair<Vec3, Vec3>> arcs_;
  std::vector<size_t> ring_ends_;  // where each ring's arcs end in arcs_
  std::vector<Chunk> chunks_;
};

const Source& world_source() {
  static const Source s(sample("world.gpkg").string(), {"name_long", true, false});
  return s;
}
const Source& nc_utm_source() {
  static const Source s(packages().nc_utm, {"NAME", false, false});
  return s;
}

// ---------------------------------------------------------------------------
// Fill against the source

struct View {
  std::string name;
  std::string args;  // packages and camera
  const Source* source;
  std::string name_field;
  bool mercator = false;  // a webmercator package: nothing expected past +-85.0511
  size_t min_land = 0;    // counted pixels inside a feature, at least
};

struct Agreement {
  size_t picks = 0, ground = 0, counted = 0, agree = 0, land = 0;
  std::vector<std::string> disagreements;
};

std::string describe(const Pick& p) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(5) << "pixel " << p.x << "," << p.y << " (lon " << p.lon
    << ", lat " << p.lat << ")";
  return s.str();
}

// Each ground pick farther than `margin_px` from a source border: its area
// is the source feature containing its ground point (none: null).
Agreement fill_against_source(const View& v, int w, int h, int step, double margin_px,
                              const fs::path& dir, PickGrid* out = nullptr) {
  Agreement a;
  const PickGrid g = pick_grid(v.args, w, h, step, v.name_field, dir);
  a.picks = g.picks.size();
  for (int r = 0; r < g.rows; ++r)
    for (int c = 0; c < g.cols; ++c) {
      const Pick& p = *g.at(c, r);
      if (!p.ground) continue;
      ++a.ground;
      const double px = g.pixel_m(c, r);
      if (px <= 0) continue;  // no neighbour on the ground: the globe's rim
      const double margin = margin_px * px;
      if (v.mercator && std::abs(p.lat) + margin / kEarthRadius / kDeg > kMercatorLimit) continue;
      if (v.source->near_border(p.lon, p.lat, margin)) continue;
      ++a.counted;
      const int f = v.source->containing(p.lon, p.lat);
      const std::string expected = f < 0 ? "" : v.source->features()[f].name;
      a.land += f >= 0;
      if (p.area == (f >= 0) && (!p.area || p.name == expected)) {
        ++a.agree;
      } else if (a.disagreements.size() < 12) {
        a.disagreements.push_back(describe(p) + ": source " +
                                  (f < 0 ? std::string("none") : expected) + ", drawn " +
                                  (p.area ? p.name : std::string("none")));
      }
    }
  if (out) *out = g;
  return a;
}

void expect_agreement(const View& v, const Agreement& a, double share) {
  std::cout << "[ " << v.name << " ] " << a.picks << " picks, " << a.ground << " on the ground, "
            << a.counted << " away from borders (" << a.land << " inside a feature): " << a.agree
            << " agree (" << std::setprecision(5) << 100.0 * double(a.agree) / double(a.counted)
            << " %)\n";
  EXPECT_GE(a.counted, 300u) << v.name << ": too few pixels away from borders";
  EXPECT_GE(a.land, v.min_land) << v.name << ": too few pixels inside a feature";
  std::string list;
  for (const std::string& d : a.disagreements)
    list += "  " + d + "\n";
  EXPECT_GE(double(a.agree), share * double(a.counted))
      << v.name << ": " << a.counted - a.agree << " of " << a.counted
      << " pixels away from borders show another area than the source's:\n"
      << list;
}

}  // namespace

// The core property: the area a pixel shows is the source polygon under its
// ground point, on the globe in both tilings (whole disc, oblique, across
// the antimeridian at Chukotka and Fiji, around the South Pole) and on the
// flat map of a local UTM package.
TEST(ViewerAreas, FillMatchesThePolygonUnderEachPixel) {
  const Packages& k = packages();
  TempDir dir;
  const std::vector<View> views = {
      {"world webmercator, the whole disc from above",
       k.world_mercator + " --globe --camera=15,15,11000000,0,0", &world_source(), "name_long",
       true, 600},
      {"world geodetic, oblique over Europe and Africa",
       k.world_geodetic + " --globe --camera=15,5,3000000,0,50", &world_source(), "name_long",
       false, 500},
      {"world webmercator, Chukotka and Alaska across the antimeridian",
       k.world_mercator + " --globe --camera=180,65,2500000,0,0", &world_source(), "name_long",
       true, 1000},
      {"world geodetic, Fiji across the antimeridian",
       k.world_geodetic + " --globe --camera=179.8,-17,500000,0,0", &world_source(), "name_long",
       false, 200},
      {"world geodetic, the South Pole", k.world_geodetic + " --globe --camera=0,-89,4000000,0,0",
       &world_source(), "name_long", false, 1000},
      {"nc.gpkg in UTM 17N, local tiling, flat", k.nc_local + " --flat --fit", &nc_utm_source(),
       "NAME", false, 400},
  };
  for (const View& v : views) {
    const Agreement a = fill_against_source(v, 320, 240, 4, 1.5, dir.path());
    expect_agreement(v, a, 0.999);
  }
}

// No gap between neighbours: on nc.gpkg's counties (webmercator) from 800 km
// (zoom 6 or so) and from 60 km (past the package's finest zoom), every
// ground point inside a county and farther than 1.5 px from the state's
// outer boundary (the union's exterior rings) shows an area.
TEST(ViewerAreas, NoLandPixelBetweenNeighboursIsUnfilled) {
  const Packages& k = packages();
  static const Source state(sample("nc.gpkg").string(), {"NAME", false, true});
  TempDir dir;
  for (const std::string camera : {"-79.5,35.5,800000,0,0", "-79.0,35.8,60000,0,0"}) {
    const PickGrid g =
        pick_grid(k.nc_mercator + " --camera=" + camera, 320, 240, 4, "NAME", dir.path());
    size_t inside = 0, unfilled = 0;
    std::string list;
    for (int r = 0; r < g.rows; ++r)
      for (int c = 0; c < g.cols; ++c) {
        const Pick& p = *g.at(c, r);
        const double px = p.ground ? g.pixel_m(c, r) : 0;
        if (px <= 0 || state.containing(p.lon, p.lat) < 0 ||
            state.near_border(p.lon, p.lat, 1.5 * px))
          continue;
        ++inside;
        if (!p.area && ++unfilled <= 12) list += "  " + describe(p) + "\n";
      }
    std::cout << "[ nc.gpkg webmercator, camera " << camera << " ] " << g.picks.size() << " picks, "
              << inside << " inside the state away from its outline, " << unfilled << " unfilled\n";
    EXPECT_GE(inside, 500u) << camera;
    EXPECT_EQ(unfilled, 0u) << camera << ": pixels inside the counties without an area:\n" << list;
  }
}

namespace {

// R's quantile(type = 7) of sorted values.
double quantile7(const std::vector<double>& v, double prob) {
  const double h = double(v.size() - 1) * prob;
  const size_t lo = size_t(std::floor(h));
  return lo + 1 < v.size() ? v[lo] + (h - double(lo)) * (v[lo + 1] - v[lo]) : v[lo];
}

// The choropleth's legend in the bottom-left corner (docs/viewer.md): the
// bounding box of its light grey background in the bottom half (x0, y0,
// x1, y1; empty when none is found).
std::array<int, 4> legend_box(const std::vector<uint8_t>& rgb, int w, int h) {
  std::array<int, 4> box{w, h, -1, -1};
  for (int y = h / 2; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const uint8_t* p = &rgb[(size_t(y) * w + x) * 3];
      if (std::min({p[0], p[1], p[2]}) >= 220 && std::max({p[0], p[1], p[2]}) <= 245 &&
          std::max({p[0], p[1], p[2]}) - std::min({p[0], p[1], p[2]}) <= 6)
        box = {std::min(box[0], x), std::min(box[1], y), std::max(box[2], x), std::max(box[3], y)};
    }
  return box;
}

std::array<int, 3> rgb_of(const std::string& hex) {
  return {std::stoi(hex.substr(1, 2), nullptr, 16), std::stoi(hex.substr(3, 2), nullptr, 16),
          std::stoi(hex.substr(5, 2), nullptr, 16)};
}

}  // namespace

// A choropleth of population density (pop / area_km2, 5 quantile classes of
// YlOrRd) at --area-opacity 1: the breaks `info --json` lists are R's
// quantile type 7 of the source's densities, and every pixel well inside a
// country (> 3 px from its borders, clear of outlines) has exactly its
// class's colour (no data: #cccccc), within 3 per channel; from orbit and
// over Chukotka, whose fill is cut at the antimeridian.
TEST(ViewerAreas, ChoroplethPixelsHaveTheirClassColour) {
  const Packages& k = packages();
  const Source& world = world_source();
  TempDir dir;
  std::vector<double> values;
  for (const Source::Feature& f : world.features()) {
    const auto pop = f.numbers.find("pop"), area = f.numbers.find("area_km2");
    if (pop != f.numbers.end() && area != f.numbers.end() && area->second > 0)
      values.push_back(pop->second / area->second);
  }
  ASSERT_GT(values.size(), 150u);
  std::sort(values.begin(), values.end());
  std::vector<double> breaks;
  for (int i = 0; i <= 5; ++i)
    breaks.push_back(quantile7(values, i / 5.0));
  const std::vector<std::string> colours = {"#ffffb2", "#fecc5c", "#fd8d3c", "#f03b20", "#bd0026"};
  const std::string no_data = "#cccccc";
  // The colour of feature i: left-closed classes, the last one closed.
  auto colour_of = [&](int i) {
    const auto& n = world.features()[i].numbers;
    const auto pop = n.find("pop"), area = n.find("area_km2");
    if (pop == n.end() || area == n.end() || !(area->second > 0)) return no_data;
    const double v = pop->second / area->second;
    int c = 0;
    while (c + 1 < 5 && v >= breaks[c + 1])
      ++c;
    return colours[c];
  };

  const RunResult info = run(vectorize() + " info " + k.world_choropleth + " --json", dir.path());
  ASSERT_EQ(info.exit_code, 0) << info.err;
  const JsonValue j = JsonValue::parse(info.out);
  const JsonValue* areas = j.find("areas");
  ASSERT_TRUE(areas && areas->find("classes")) << info.out;
  const auto& classes = areas->find("classes")->array();
  ASSERT_EQ(classes.size(), 5u) << areas->text();
  auto same = [](double a, double b) {
    return std::abs(a - b) <= 1e-9 * std::max(std::abs(a), std::abs(b));
  };
  for (size_t i = 0; i < 5; ++i) {
    const double lo = classes[i].find("min")->number(), hi = classes[i].find("max")->number();
    EXPECT_TRUE(same(lo, breaks[i])) << std::setprecision(17) << "class " << i << ": min " << lo
                                     << ", quantile type 7 " << breaks[i];
    EXPECT_TRUE(same(hi, breaks[i + 1])) << std::setprecision(17) << "class " << i << ": max " << hi
                                         << ", quantile type 7 " << breaks[i + 1];
    EXPECT_EQ(classes[i].find("color")->string(), colours[i]) << "class " << i;
  }

  for (const std::string camera : {"15,15,11000000,0,0", "180,65,2500000,0,0"}) {
    const std::string args = k.world_choropleth + " --globe --area-opacity 1 --camera=" + camera;
    const std::string png = (dir / "choropleth.png").string();
    const RunResult r =
        run(viewer() + " " + args + " --size 320x240 --snapshot " + png, dir.path());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    int w = 0, h = 0;
    const std::vector<uint8_t> rgb = read_rgb(png, w, h);
    ASSERT_EQ(w, 320);
    ASSERT_EQ(h, 240);
    // Left out: the legend and 3 px around it.
    const auto legend = legend_box(rgb, w, h);
    EXPECT_GT(legend[2] - legend[0], 40) << camera << ": no legend in the bottom-left corner";
    EXPECT_GT(legend[3] - legend[1], 40) << camera << ": no legend in the bottom-left corner";
    // The grid includes the middle column: the antimeridian in the second view.
    const PickGrid g = pick_grid(args, 320, 240, 4, "name_long", dir.path(), 0);
    size_t counted = 0, right = 0;
    std::map<std::string, size_t> per_colour;
    std::string list;
    for (int row = 0; row < g.rows; ++row)
      for (int col = 0; col < g.cols; ++col) {
        const Pick& p = *g.at(col, row);
        const double px = p.ground ? g.pixel_m(col, row) : 0;
        if (px <= 0 || std::abs(p.lat) > kMercatorLimit - 1) continue;
        if (p.x >= legend[0] - 3 && p.x <= legend[2] + 3 && p.y >= legend[1] - 3 &&
            p.y <= legend[3] + 3)
          continue;
        const int f = world.containing(p.lon, p.lat);
        if (f < 0 || world.near_border(p.lon, p.lat, 3 * px)) continue;
        ++counted;
        const std::string want = colour_of(f);
        ++per_colour[want];
        const auto c = rgb_of(want);
        const uint8_t* got = &rgb[(size_t(p.y) * w + p.x) * 3];
        if (std::abs(got[0] - c[0]) <= 3 && std::abs(got[1] - c[1]) <= 3 &&
            std::abs(got[2] - c[2]) <= 3) {
          ++right;
        } else if (counted - right <= 12) {
          list +=
              "  " + describe(p) + " in " + world.features()[f].name + ": " + want +
              " expected, drawn " + std::to_string(got[0]) + "," + std::to_string(got[1]) + "," +
              std::to_string(got[2]) +
              (std::abs(std::abs(p.lon) - 180) * kDeg * kEarthRadius * std::cos(p.lat * kDeg) < px
                   ? " (on the antimeridian, where the source is split: no border)"
                   : "") +
              "\n";
        }
      }
    std::cout << "[ choropleth, camera " << camera << " ] " << counted
              << " pixels well inside countries, " << right << " of their class colour (";
    for (const auto& [colour, n] : per_colour)
      std::cout << colour << " " << n << " ";
    std::cout << ")\n";
    EXPECT_GE(counted, 300u) << camera;
    EXPECT_EQ(right, counted) << camera << ": pixels not of their class colour:\n" << list;
  }
}

// Areas of one tiling over a terrain of another (webmercator countries over
// the geodetic etopo20): the fill still follows the source under each pixel
// (now the terrain's surface), and that surface has heights.
TEST(ViewerAreas, AreasOverTerrainInAnotherTiling) {
  const Packages& k = packages();
  TempDir dir;
  const View v{"world webmercator over etopo20 geodetic, oblique over the Alps",
               k.etopo + " " + k.world_mercator + " --globe --camera=10,40,1500000,0,55",
               &world_source(),
               "name_long",
               true,
               500};
  PickGrid g;
  const Agreement a = fill_against_source(v, 320, 240, 4, 1.5, dir.path(), &g);
  expect_agreement(v, a, 0.999);
  size_t land = 0, raised = 0;
  double highest = 0;
  for (const Pick& p : g.picks)
    if (p.ground && p.area) {
      ++land;
      raised += std::abs(p.height) > 100;
      highest = std::max(highest, p.height);
    }
  std::cout << "[ " << v.name << " ] " << land << " picks on an area, " << raised
            << " of them more than 100 m from height 0, the highest at " << highest << " m\n";
  EXPECT_GE(raised, land / 4) << "the picks' heights show no terrain under the areas";
  EXPECT_GT(highest, 500) << "no mountain under the Alps";
}

// North Carolina's sudden infant deaths per birth (SID74 / BIR74, 1974) in
// 5 quantile classes of YlOrRd, the whole state (--fit) on the flat map,
// against tests/data/render/viewer_areas_nc.png (make_expected.sh).
TEST(ViewerAreas, MatchesExpected) {
  const Packages& k = packages();
  TempDir dir;
  const std::string out = (dir / "nc.png").string();
  const RunResult r =
      run(viewer() + " " + k.nc_choropleth + " --fit --size 320x200 --snapshot " + out, dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  expect_image(out, "viewer_areas_nc");
}

namespace {

// A damaged area package, as a user may meet one: every tile's blob
// replaced by random bytes. `validate` says so (exit 1, naming a tile); the
// viewer warns about each broken tile once, draws the frame and exits 0, and
// its statistics count the broken tiles.
TEST(ViewerAreas, CorruptAreaTilesWarnAndTheFrameGoesOn) {
  const Packages& k = packages();
  TempDir dir;
  const std::string pkg = (dir / "broken.mbtiles").string();
  fs::copy_file(k.nc_mercator, pkg);
  const RunResult s =
      run("sqlite3 " + pkg + " \"UPDATE blobs SET tile_data = randomblob(64);\"", dir.path());
  ASSERT_EQ(s.exit_code, 0) << s.err;
  const RunResult v = run(vectorize() + " validate " + pkg, dir.path());
  EXPECT_EQ(v.exit_code, 1) << v.out << v.err;
  EXPECT_NE(v.out.find("tile"), std::string::npos) << v.out;
  const RunResult r =
      run(viewer() + " " + pkg + " --fit --stats --frames 1 --size 160x100", dir.path());
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("area tile"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("the areas of its coarser or finer tiles are drawn there"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(r.out.find("\"broken_area_tiles\": 0"), std::string::npos) << r.out;
}

}  // namespace

namespace {

// --pick-format json with an area, a line and a point package drawn
// together: at a place's own position the chart there (its id and values) and
// the county filled under it; on a county's border vertex (from OGR) the line
// drawn there; each with the ground's lon/lat under the pixel.
TEST(ViewerAreas, PickJsonNamesTheAreaLineAndChartUnderAPixel) {
  const Packages& k = packages();
  TempDir dir;
  // Wake county's first border vertex, in lon/lat.
  GDALAllRegister();
  GDALDatasetH ds =
      GDALOpenEx((samples() / "nc.gpkg").c_str(), GDAL_OF_VECTOR, nullptr, nullptr, nullptr);
  ASSERT_NE(ds, nullptr);
  OGRLayerH layer = GDALDatasetGetLayer(ds, 0);
  OGR_L_SetAttributeFilter(layer, "NAME = 'Wake'");
  OGRFeatureH f = OGR_L_GetNextFeature(layer);
  ASSERT_NE(f, nullptr);
  OGRGeometryH g = OGR_G_Clone(OGR_F_GetGeometryRef(f));
  OGRSpatialReferenceH to = OSRNewSpatialReference(nullptr);
  OSRImportFromEPSG(to, 4326);
  OSRSetAxisMappingStrategy(to, OAMS_TRADITIONAL_GIS_ORDER);
  ASSERT_EQ(OGR_G_TransformTo(g, to), OGRERR_NONE);
  OGRGeometryH ring = OGR_G_GetGeometryRef(OGR_G_GetGeometryRef(g, 0), 0);
  const double bx = OGR_G_GetX(ring, 0), by = OGR_G_GetY(ring, 0);
  OGR_G_DestroyGeometry(g);
  OSRDestroySpatialReference(to);
  OGR_F_Destroy(f);
  GDALClose(ds);

  const std::string lines = (dir / "l.mbtiles").string(), points = (dir / "p.mbtiles").string();
  std::ofstream(dir / "p.csv") << "name,lon,lat,v\nRaleigh,-78.64,35.78,5\n";
  ASSERT_EQ(run(vectorize() + " lines -q " + (samples() / "nc.gpkg").string() +
                    " --max-zoom 9 -o " + lines,
                dir.path())
                .exit_code,
            0);
  ASSERT_EQ(run(vectorize() + " points -q " + (dir / "p.csv").string() +
                    " --xy lon,lat --fields v --label-field name -o " + points,
                dir.path())
                .exit_code,
            0);
  char place[64], border[64];
  std::snprintf(place, sizeof place, "@-78.64,35.78");
  std::snprintf(border, sizeof border, "@%.7f,%.7f", bx, by);
  const RunResult r = run(viewer() + " " + k.nc_mercator + " " + lines + " " + points +
                              " --size 320x200 --camera=-78.6,35.8,120000,0,0 --pick-format json" +
                              " --pick " + place + " --pick " + border,
                          dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::istringstream out(r.out);
  std::vector<JsonValue> picks;
  for (std::string line; std::getline(out, line);)
    picks.push_back(JsonValue::parse(line));
  ASSERT_EQ(picks.size(), 2u) << r.out;
  const JsonValue* chart = picks[0].find("chart");
  ASSERT_TRUE(chart && chart->is_object()) << r.out;
  EXPECT_EQ(chart->find("id")->number(), 1);
  EXPECT_EQ(chart->find("values")->find("v")->number(), 5);
  const JsonValue* area = picks[0].find("area");
  ASSERT_TRUE(area && area->is_object()) << r.out;
  EXPECT_EQ(area->find("attributes")->find("NAME")->string(), "Wake");
  EXPECT_NEAR(picks[0].find("lon")->number(), -78.64, 0.01);
  EXPECT_NEAR(picks[0].find("lat")->number(), 35.78, 0.01);
  const JsonValue* line = picks[1].find("line");
  ASSERT_TRUE(line && line->is_object()) << r.out;
  EXPECT_GE(line->find("id")->number(), 1);
  EXPECT_EQ(line->find("layer")->string(), "nc.gpkg");
  EXPECT_NEAR(picks[1].find("lon")->number(), bx, 0.01);
  EXPECT_NEAR(picks[1].find("lat")->number(), by, 0.01);
}

}  // namespace
