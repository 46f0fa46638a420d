// globe-view's labels (--labels, --labels-json) as a user runs them, checked
// against references written here that share no code with the viewer: the
// packages come from globe-vectorize (world.gpkg's countries, airways.geojson's
// airways, us_airport_flights.csv's airports, and grids of named places and
// curved lines this file writes), the terrain from globe-tiler (etopo20.tif),
// and every check reads the JSON the viewer writes per frame:
//
// - No two visible labels (alpha > 0) overlap: boxes of point and area labels
//   never intersect; a line label's glyphs (a disc around each glyph centre)
//   touch no other label's box or glyphs. A global disc, oblique views of
//   Europe with airways and countries, and every frame of the paths below.
// - Terrain hides labels, and only terrain: from the eye (WGS84, this file's
//   camera model of --camera) to each place's ground point (etopo20.tif read
//   with GDAL, bilinear between pixel centres, times --exaggeration) a ray
//   is marched; a label whose sight line the relief crosses by a clear
//   margin is never drawn, one whose sight line clears the relief by a
//   clear margin, whose box is on screen and overlaps no drawn label, is
//   drawn. Low oblique views across the Himalaya and the Alps.
// - Stability along camera paths of 60 poses (a pan, a zoom-in, an orbit):
//   no label goes off-on-off or on-off-on within fewer than 3 frames, and
//   during the zoom-in none is dropped while its anchor stays in view.
// - Association and shape: a point label's box lies beside its anchor's
//   projection, on one of its four sides (0..20 px from it, centred on it
//   within 4 px; without charts, which labels stand beside); a line
//   label's glyph centres lie on the projected line (within half the text
//   height), neighbouring glyphs turn by at most 45 degrees, every glyph is
//   upright.
//
// The camera model (CameraModelAgreesWithPointLabels) is checked first
// against the viewer's point-label boxes over zero heights.
#include <gtest/gtest.h>

#include <gdal.h>
#include <sqlite3.h>

#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <numbers>
#include <sstream>

#include "render_fixtures.hpp"
#include "test_paths.hpp"
#include "test_support.hpp"
#include "tileformat/json.hpp"

namespace {

using namespace globe_test;
using tileformat::JsonValue;

constexpr double kDeg = std::numbers::pi / 180;
constexpr double kA = 6378137.0;  // WGS84
constexpr double kF = 1 / 298.257223563;
constexpr double kE2 = kF * (2 - kF);

// ---------------------------------------------------------------------------
// Geometry: WGS84 and the camera of --camera

struct Vec3 {
  double x = 0, y = 0, z = 0;
};
Vec3 operator+(Vec3 a, Vec3 b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
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

// Geodetic lon/lat (degrees) and height above the ellipsoid -> ECEF metres.
Vec3 ecef(double lon, double lat, double h) {
  const double sl = std::sin(lat * kDeg), cl = std::cos(lat * kDeg);
  const double n = kA / std::sqrt(1 - kE2 * sl * sl);
  return {(n + h) * cl * std::cos(lon * kDeg), (n + h) * cl * std::sin(lon * kDeg),
          (n * (1 - kE2) + h) * sl};
}
// The ellipsoid's normal (local up) at lon/lat.
Vec3 up_at(double lon, double lat) {
  return {std::cos(lat * kDeg) * std::cos(lon * kDeg), std::cos(lat * kDeg) * std::sin(lon * kDeg),
          std::sin(lat * kDeg)};
}

struct Geodetic {
  double lon = 0, lat = 0, h = 0;
};
// ECEF -> geodetic, by fixed-point iteration on the latitude (away from the
// poles, which no view here comes near).
Geodetic geodetic(Vec3 p) {
  const double r = std::hypot(p.x, p.y);
  double lat = std::atan2(p.z, r * (1 - kE2)), h = 0;
  for (int i = 0; i < 3; ++i) {
    const double s = std::sin(lat), n = kA / std::sqrt(1 - kE2 * s * s);
    h = r / std::cos(lat) - n;
    lat = std::atan2(p.z, r * (1 - kE2 * n / (n + h)));
  }
  const double s = std::sin(lat), n = kA / std::sqrt(1 - kE2 * s * s);
  h = r / std::cos(lat) - n;
  return {std::atan2(p.y, p.x) / kDeg, lat / kDeg, h};
}

struct Pose {
  double lon = 0, lat = 0, height = 0, heading = 0, pitch = 0;
};
std::string pose_text(const Pose& p) {
  std::ostringstream s;
  s << std::setprecision(10) << p.lon << "," << p.lat << "," << p.height << "," << p.heading << ","
    << p.pitch;
  return s.str();
}

// --camera as globe-view documents it: the eye at lon/lat and `height`
// metres above the ellipsoid; the local east-north-up frame there; heading
// turns the view clockwise from north, pitch 0 looks straight down along
// the ellipsoid's normal and 90 horizontally; a vertical field of view of
// 45 degrees over the image's height; pixels from the top-left.
class Camera {
 public:
  Camera(const Pose& p, int width, int height, double fov_deg = 45) : w_(width), h_(height) {
    eye = ecef(p.lon, p.lat, p.height);
    const double lo = p.lon * kDeg, la = p.lat * kDeg;
    const Vec3 east{-std::sin(lo), std::cos(lo), 0};
    const Vec3 north{-std::sin(la) * std::cos(lo), -std::sin(la) * std::sin(lo), std::cos(la)};
    const Vec3 up = up_at(p.lon, p.lat);
    const double hd = p.heading * kDeg, pt = p.pitch * kDeg;
    const Vec3 ahead = std::cos(hd) * north + std::sin(hd) * east;
    forward_ = std::sin(pt) * ahead - std::cos(pt) * up;
    up_ = std::sin(pt) * up + std::cos(pt) * ahead;
    right_ = cross(forward_, up_);
    focal = 0.5 * height / std::tan(0.5 * fov_deg * kDeg);
  }
  // The pixel of `p` and its depth along the view; false behind the eye.
  bool project(Vec3 p, double& x, double& y, double* depth = nullptr) const {
    const Vec3 d = p - eye;
    const double z = dot(d, forward_);
    if (z <= 1) return false;
    x = 0.5 * w_ + focal * dot(d, right_) / z;
    y = 0.5 * h_ - focal * dot(d, up_) / z;
    if (depth) *depth = z;
    return true;
  }
  bool inside(double x, double y, double inset = 0) const {
    return x >= inset && y >= inset && x <= w_ - inset && y <= h_ - inset;
  }
  int width() const { return w_; }
  int height() const { return h_; }

  Vec3 eye;
  double focal = 0;

 private:
  int w_, h_;
  Vec3 forward_, up_, right_;
};

// ---------------------------------------------------------------------------
// The relief: etopo20.tif read with GDAL

// Heights in metres, bilinear between pixel centres (the GeoTIFF says
// AREA_OR_POINT=Area), wrapping in longitude (the grid starts at 20 E and
// its last column repeats its first one turn later).
class Relief {
 public:
  explicit Relief(const std::string& path) {
    gdal_setup();
    GDALDatasetH ds = GDALOpen(path.c_str(), GA_ReadOnly);
    if (!ds) return;
    w_ = GDALGetRasterXSize(ds);
    h_ = GDALGetRasterYSize(ds);
    GDALGetGeoTransform(ds, gt_);
    z_.resize(size_t(w_) * h_);
    if (GDALRasterIO(GDALGetRasterBand(ds, 1), GF_Read, 0, 0, w_, h_, z_.data(), w_, h_,
                     GDT_Float32, 0, 0) != CE_None)
      z_.clear();
    GDALClose(ds);
    turn_ = int(std::lround(360 / gt_[1]));
  }
  bool ok() const { return !z_.empty() && turn_ > 1 && turn_ <= w_ && h_ > 1; }
  double height(double lon, double lat) const {
    double fx = std::fmod((lon - gt_[0]) / gt_[1] - 0.5, double(turn_));
    if (fx < 0) fx += turn_;
    const double fy = std::clamp((lat - gt_[3]) / gt_[5] - 0.5, 0.0, double(h_ - 1));
    const int i0 = std::min(int(fx), turn_ - 1), i1 = (i0 + 1) % turn_;
    const int j0 = std::min(int(fy), h_ - 2), j1 = j0 + 1;
    const double tx = fx - i0, ty = fy - j0;
    auto at = [&](int i, int j) { return double(z_[size_t(j) * w_ + i]); };
    return (at(i0, j0) * (1 - tx) + at(i1, j0) * tx) * (1 - ty) +
           (at(i0, j1) * (1 - tx) + at(i1, j1) * tx) * ty;
  }

 private:
  int w_ = 0, h_ = 0, turn_ = 0;
  double gt_[6] = {0, 1, 0, 0, 0, -1};
  std::vector<float> z_;
};

const Relief& etopo_relief() {
  static const Relief r(sample("etopo20.tif").string());
  return r;
}

// ---------------------------------------------------------------------------
// The labels JSON

struct Glyph {
  double x = 0, y = 0, angle = 0;
};
struct Label {
  std::string text, placement, package;
  long long feature = 0, id = 0;
  double lon = 0, lat = 0, alpha = 0;
  std::array<double, 4> box{};  // x0, y0, x1, y1
  std::vector<Glyph> glyphs;
  bool visible() const { return alpha > 0; }
  std::string key() const {
    return fs::path(package).filename().string() + "#" + std::to_string(id) + " '" + text + "'";
  }
  double width() const { return box[2] - box[0]; }
  double height() const { return box[3] - box[1]; }
};
struct Frame {
  int index = 0;
  Pose pose;
  long long candidates = 0, shown = 0, occluded = 0, illegible = 0;
  std::vector<Label> labels;
  size_t visible_count() const {
    return size_t(
        std::count_if(labels.begin(), labels.end(), [](const Label& l) { return l.visible(); }));
  }
};
struct LabelsJson {
  int width = 0, height = 0;
  std::vector<Frame> frames;
};

const JsonValue& member(const JsonValue& o, const char* name) {
  const JsonValue* v = o.find(name);
  if (!v)
    throw std::runtime_error(std::string("no \"") + name + "\" in " + o.text().substr(0, 200));
  return *v;
}
double number(const JsonValue& o, const char* name) {
  return member(o, name).number();
}

LabelsJson parse_labels(const std::string& text) {
  LabelsJson out;
  const JsonValue j = JsonValue::parse(text);
  out.width = int(number(j, "width"));
  out.height = int(number(j, "height"));
  for (const JsonValue& f : member(j, "frames").array()) {
    Frame fr;
    fr.index = int(number(f, "frame"));
    const auto& pose = member(f, "pose").array();
    if (pose.size() != 5) throw std::runtime_error("a pose of " + std::to_string(pose.size()));
    fr.pose = {pose[0].number(), pose[1].number(), pose[2].number(), pose[3].number(),
               pose[4].number()};
    fr.candidates = (long long)number(f, "candidates");
    fr.shown = (long long)number(f, "shown");
    fr.occluded = (long long)number(f, "occluded");
    fr.illegible = (long long)number(f, "illegible");
    for (const JsonValue& l : member(f, "labels").array()) {
      Label lb;
      lb.text = member(l, "text").string();
      lb.placement = member(l, "placement").string();
      const JsonValue& src = member(l, "source");
      lb.package = member(src, "package").string();
      lb.feature = (long long)number(src, "feature");
      lb.id = (long long)number(src, "label");
      const auto& anchor = member(l, "anchor").array();
      const auto& box = member(l, "box").array();
      if (anchor.size() != 2 || box.size() != 4) throw std::runtime_error("bad anchor or box");
      lb.lon = anchor[0].number();
      lb.lat = anchor[1].number();
      for (int i = 0; i < 4; ++i)
        lb.box[i] = box[i].number();
      lb.alpha = number(l, "alpha");
      if (const JsonValue* glyphs = l.find("glyphs"); glyphs && glyphs->is_array())
        for (const JsonValue& g : glyphs->array()) {
          const auto& v = g.array();
          if (v.size() != 3) throw std::runtime_error("a glyph of " + std::to_string(v.size()));
          lb.glyphs.push_back({v[0].number(), v[1].number(), v[2].number()});
        }
      fr.labels.push_back(std::move(lb));
    }
    out.frames.push_back(std::move(fr));
  }
  return out;
}

// Runs `globe-view ARGS --size WxH --snapshot --labels-json` in `dir`; the
// labels it wrote (no frames when it failed: a test failure).
LabelsJson view_labels(const std::string& args, int w, int h, const fs::path& dir,
                       const std::string& tag = "view") {
  const fs::path json = dir / (tag + ".json"), png = dir / (tag + ".png");
  const std::string cmd = viewer() + " " + args + " --size " + std::to_string(w) + "x" +
                          std::to_string(h) + " --snapshot " + png.string() + " --labels-json " +
                          json.string();
  const auto start = std::chrono::steady_clock::now();
  const RunResult r = run(cmd, dir);
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_EQ(r.exit_code, 0) << cmd << "\n" << r.err;
  if (r.exit_code != 0) return {};
  std::cout << "[globe-view " << tag << ": " << std::fixed << std::setprecision(1) << s << " s]\n";
  try {
    LabelsJson out = parse_labels(read_file(json));
    EXPECT_EQ(out.width, w);
    EXPECT_EQ(out.height, h);
    return out;
  } catch (const std::exception& e) {
    ADD_FAILURE() << json << ": " << e.what();
    return {};
  }
}

// What globe-view --pick says is at a pixel: the ground point there, or
// none (sky).
struct PickAt {
  bool ground = false;
  double lon = 0, lat = 0, height = 0;
};
std::vector<PickAt> view_picks(const std::string& args, int w, int h,
                               const std::vector<std::pair<int, int>>& pixels,
                               const fs::path& dir) {
  std::string cmd = viewer() + " " + args + " --size " + std::to_string(w) + "x" +
                    std::to_string(h) + " --snapshot " + (dir / "picks.png").string() +
                    " --pick-format json";
  for (const auto& [x, y] : pixels)
    cmd += " --pick " + std::to_string(x) + "," + std::to_string(y);
  const RunResult r = run(cmd, dir);
  std::vector<PickAt> out;
  if (r.exit_code != 0) return out;
  std::istringstream lines(r.out);
  std::string line;
  while (std::getline(lines, line)) {
    if (line.empty()) continue;
    try {
      const JsonValue j = JsonValue::parse(line);
      PickAt p;
      const JsonValue* lon = j.find("lon");
      const JsonValue* lat = j.find("lat");
      const JsonValue* height = j.find("height");
      p.ground = lon && lat && lon->is_number() && lat->is_number();
      if (p.ground) {
        p.lon = lon->number();
        p.lat = lat->number();
        p.height = height && height->is_number() ? height->number() : 0;
      }
      out.push_back(p);
    } catch (const std::exception&) {
      out.push_back({});
    }
  }
  return out;
}

// ---------------------------------------------------------------------------
// Inputs written here and the packages, built once per build tree

// A grid of named places (NAME: prefix and a 3-digit number, row-major from
// the south-west); all of one priority.
struct Grid {
  std::string prefix;
  double lon0, lat0, dlon, dlat;
  int cols, rows;
};
struct Place {
  std::string name;
  double lon, lat;
};
std::vector<Place> grid_places(const Grid& g) {
  std::vector<Place> out;
  for (int j = 0; j < g.rows; ++j)
    for (int i = 0; i < g.cols; ++i) {
      char name[16];
      std::snprintf(name, sizeof name, "%s%03d", g.prefix.c_str(), j * g.cols + i);
      out.push_back({name, g.lon0 + i * g.dlon, g.lat0 + j * g.dlat});
    }
  return out;
}
// Around the Himalaya: the Ganges plain (24.5-27.5 N), the range
// (28-29 N) and the Tibetan plateau (29.5-33.5 N).
const Grid kHimalaya{"H", 80.25, 24.5, 0.5, 1.0, 20, 10};
// Around the Alps: the Po plain and Liguria, the range, the Swiss
// plateau and Bavaria (43.75-48.25 N, 5.25-14.75 E).
const Grid kAlps{"A", 5.25, 43.75, 0.5, 0.5, 20, 10};
// Sparse enough that every label gets its first place (the camera check).
const Grid kSparse{"S", 4, 42, 3, 2, 5, 5};

void write_grid_csv(const fs::path& path, const Grid& g) {
  std::ofstream out(path);
  out << "name,pop,lon,lat\n" << std::setprecision(10);
  for (const Place& p : grid_places(g))
    out << p.name << ",100," << p.lon << "," << p.lat << "\n";
}

// Ten named sine waves across Europe (three periods over 24 degrees of
// longitude, 0.6 degrees of amplitude): labels that must bend.
void write_curves_geojson(const fs::path& path) {
  const char* names[] = {"Curve Alpha", "Curve Bravo",   "Curve Charlie", "Curve Delta",
                         "Curve Echo",  "Curve Foxtrot", "Curve Golf",    "Curve Hotel",
                         "Curve India", "Curve Juliett"};
  std::ofstream out(path);
  out << std::setprecision(9) << "{\"type\":\"FeatureCollection\",\"features\":[";
  for (int k = 0; k < 10; ++k) {
    out << (k ? "," : "") << "{\"type\":\"Feature\",\"properties\":{\"name\":\"" << names[k]
        << "\"},\"geometry\":{\"type\":\"LineString\",\"coordinates\":[";
    for (int i = 0; i <= 200; ++i) {
      const double t = i / 200.0;
      out << (i ? "," : "") << "[" << -2 + 24 * t << ","
          << 40 + 1.5 * k + 0.6 * std::sin(t * 2 * std::numbers::pi * 3 + k) << "]";
    }
    out << "]}}";
  }
  out << "]}\n";
}

struct Packages {
  fs::path dir;
  std::string etopo, world, airways, curves, airports, himalaya, alps, sparse;
};

const Packages& packages() {
  static const Packages p = [] {
    Packages k;
    k.dir = shared_folder("globe-view-labels", [](const fs::path& dir) {
      auto at = [&](const char* name) { return (dir / name).string(); };
      write_grid_csv(dir / "himalaya.csv", kHimalaya);
      write_grid_csv(dir / "alps.csv", kAlps);
      write_grid_csv(dir / "sparse.csv", kSparse);
      write_curves_geojson(dir / "curves.geojson");
      const std::string v = vectorize();
      const std::string grid = " --xy lon,lat --fields pop --label-field name -o ";
      return run_all({tiler() + " terrain -q --tiling geodetic " + sample("etopo20.tif").string() +
                          " -o " + at("etopo.mbtiles"),
                      v + " areas -q " + sample("world.gpkg").string() +
                          " --label-field name_long -o " + at("world.mbtiles"),
                      v + " lines -q " + sample("airways.geojson").string() +
                          " --label-field name -o " + at("airways.mbtiles"),
                      v + " lines -q " + at("curves.geojson") + " --label-field name -o " +
                          at("curves.mbtiles"),
                      v + " points -q " + sample("us_airport_flights.csv").string() +
                          " --xy longitude,latitude --fields west,midwest,south,northeast,other"
                          " --label-field name -o " +
                          at("airports.mbtiles"),
                      v + " points -q " + at("himalaya.csv") + grid + at("himalaya.mbtiles"),
                      v + " points -q " + at("alps.csv") + grid + at("alps.mbtiles"),
                      v + " points -q " + at("sparse.csv") + grid + at("sparse.mbtiles")},
                     dir);
    });
    auto at = [&](const char* name) { return (k.dir / name).string(); };
    k.etopo = at("etopo.mbtiles");
    k.world = at("world.mbtiles");
    k.airways = at("airways.mbtiles");
    k.curves = at("curves.mbtiles");
    k.airports = at("airports.mbtiles");
    k.himalaya = at("himalaya.mbtiles");
    k.alps = at("alps.mbtiles");
    k.sparse = at("sparse.mbtiles");
    return k;
  }();
  return p;
}

// A line package's label paths (lon, lat pairs), by label id, read from its
// labels table with SQLite.
std::map<long long, std::vector<std::array<double, 2>>> label_paths(const std::string& package) {
  std::map<long long, std::vector<std::array<double, 2>>> out;
  sqlite3* db = nullptr;
  if (sqlite3_open_v2(package.c_str(), &db, SQLITE_OPEN_READONLY, nullptr) != SQLITE_OK) {
    ADD_FAILURE() << "cannot open " << package;
    sqlite3_close(db);
    return out;
  }
  sqlite3_stmt* st = nullptr;
  if (sqlite3_prepare_v2(db, "SELECT id, path FROM labels WHERE path IS NOT NULL", -1, &st,
                         nullptr) != SQLITE_OK) {
    ADD_FAILURE() << package << ": " << sqlite3_errmsg(db);
    sqlite3_close(db);
    return out;
  }
  while (sqlite3_step(st) == SQLITE_ROW) {
    const long long id = sqlite3_column_int64(st, 0);
    const auto* blob = static_cast<const unsigned char*>(sqlite3_column_blob(st, 1));
    const int bytes = sqlite3_column_bytes(st, 1);
    EXPECT_EQ(bytes % 16, 0) << "label " << id << ": a path of " << bytes << " bytes";
    auto& path = out[id];
    for (int i = 0; i + 16 <= bytes; i += 16) {
      std::array<double, 2> v{};
      // Little-endian float64 (this machine is little-endian too).
      std::memcpy(v.data(), blob + i, 16);
      path.push_back(v);
    }
  }
  sqlite3_finalize(st);
  sqlite3_close(db);
  return out;
}

// ---------------------------------------------------------------------------
// Shared checks

// A line label's text height: the side of its box its glyph centres do not
// span (the text's own height, with the box's padding).
double text_height(const Label& l) {
  if (l.glyphs.empty()) return l.height();
  double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
  for (const Glyph& g : l.glyphs) {
    x0 = std::min(x0, g.x), x1 = std::max(x1, g.x);
    y0 = std::min(y0, g.y), y1 = std::max(y1, g.y);
  }
  return std::max(1.0, std::min(l.width() - (x1 - x0), l.height() - (y1 - y0)));
}
// A glyph's footprint: a disc of a quarter of the text height (with its
// padding) around its centre, about a third of the font size: inside the
// ink of any letter but the narrowest.
double glyph_radius(const Label& l) {
  return 0.25 * text_height(l);
}

// Whether two boxes come closer than `pad` (a negative pad: overlap by more
// than -pad).
bool boxes_intersect(const std::array<double, 4>& a, const std::array<double, 4>& b,
                     double pad = 0) {
  return std::min(a[2], b[2]) - std::max(a[0], b[0]) > -pad &&
         std::min(a[3], b[3]) - std::max(a[1], b[1]) > -pad;
}
bool disc_meets_box(double x, double y, double r, const std::array<double, 4>& b) {
  const double dx = std::max({b[0] - x, 0.0, x - b[2]}), dy = std::max({b[1] - y, 0.0, y - b[3]});
  return dx * dx + dy * dy < r * r;
}

// Whether two visible labels overlap (boxes; a line label by its glyphs).
bool overlap(const Label& a, const Label& b) {
  const bool la = !a.glyphs.empty(), lb = !b.glyphs.empty();
  if (!la && !lb) return boxes_intersect(a.box, b.box, -1e-3);
  // Glyph discs lie inside their label's box.
  if (!boxes_intersect(a.box, b.box)) return false;
  if (la && lb) {
    const double r = glyph_radius(a) + glyph_radius(b);
    for (const Glyph& g : a.glyphs)
      for (const Glyph& h : b.glyphs)
        if (std::hypot(g.x - h.x, g.y - h.y) < r) return true;
    return false;
  }
  const Label& line = la ? a : b;
  const Label& other = la ? b : a;
  const double r = glyph_radius(line);
  for (const Glyph& g : line.glyphs)
    if (disc_meets_box(g.x, g.y, r, other.box)) return true;
  return false;
}

std::string describe(const Label& l) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(1) << l.key() << " (" << l.placement << ", alpha " << l.alpha
    << ") box [" << l.box[0] << ", " << l.box[1] << ", " << l.box[2] << ", " << l.box[3] << "]";
  if (!l.glyphs.empty()) s << ", " << l.glyphs.size() << " glyphs";
  return s.str();
}

// How far apart two visible labels are (negative: by how much they
// overlap): boxes, or a line label's glyph discs.
double gap(const Label& a, const Label& b) {
  auto box_gap = [](const std::array<double, 4>& p, const std::array<double, 4>& q) {
    const double dx = std::max(p[0], q[0]) - std::min(p[2], q[2]);
    const double dy = std::max(p[1], q[1]) - std::min(p[3], q[3]);
    return dx > 0 && dy > 0 ? std::hypot(dx, dy) : std::max(dx, dy);
  };
  auto disc_gap = [](const Glyph& g, double r, const std::array<double, 4>& q) {
    const double dx = std::max({q[0] - g.x, 0.0, g.x - q[2]});
    const double dy = std::max({q[1] - g.y, 0.0, g.y - q[3]});
    return dx == 0 && dy == 0 ? -r : std::hypot(dx, dy) - r;
  };
  const bool la = !a.glyphs.empty(), lb = !b.glyphs.empty();
  if (!la && !lb) return box_gap(a.box, b.box);
  double out = 1e300;
  if (la && lb) {
    const double r = glyph_radius(a) + glyph_radius(b);
    for (const Glyph& g : a.glyphs)
      for (const Glyph& h : b.glyphs)
        out = std::min(out, std::hypot(g.x - h.x, g.y - h.y) - r);
    return out;
  }
  const Label& line = la ? a : b;
  const Label& other = la ? b : a;
  for (const Glyph& g : line.glyphs)
    out = std::min(out, disc_gap(g, glyph_radius(line), other.box));
  return out;
}

// Every pair of visible labels of every frame; returns the overlapping pairs
// (a test failure each, the first 10 described).
size_t expect_no_overlap(const LabelsJson& v, const std::string& what) {
  size_t bad = 0, pairs = 0;
  double closest = 1e300;
  for (const Frame& f : v.frames) {
    std::vector<const Label*> shown;
    for (const Label& l : f.labels)
      if (l.visible()) shown.push_back(&l);
    for (size_t i = 0; i < shown.size(); ++i)
      for (size_t j = i + 1; j < shown.size(); ++j) {
        ++pairs;
        closest = std::min(closest, gap(*shown[i], *shown[j]));
        if (overlap(*shown[i], *shown[j])) {
          if (++bad <= 10)
            ADD_FAILURE() << what << ", frame " << f.index << ": " << describe(*shown[i])
                          << " overlaps " << describe(*shown[j]);
        }
      }
  }
  EXPECT_EQ(bad, 0u) << what << ": overlapping pairs of visible labels";
  std::cout << what << ": " << pairs << " pairs of visible labels, " << bad
            << " overlapping; the closest " << std::fixed << std::setprecision(1)
            << (pairs ? closest : 0.0) << " px apart\n";
  return bad;
}

void print_rates(const LabelsJson& v, const std::string& what) {
  for (const Frame& f : v.frames) {
    std::cout << what << " frame " << f.index << ": shown " << f.visible_count() << " of "
              << f.candidates << " candidates (" << std::fixed << std::setprecision(1)
              << (f.candidates ? 100.0 * f.visible_count() / f.candidates : 0.0) << " %); occluded "
              << f.occluded << ", illegible " << f.illegible << "\n";
  }
}

const Label* find_label(const Frame& f, const std::string& text) {
  for (const Label& l : f.labels)
    if (l.text == text) return &l;
  return nullptr;
}

// ---------------------------------------------------------------------------
// The sight line from the eye to a ground point, marched over the relief

enum class Sight { kVisible, kHidden, kUnclear };

// Margins: kMarginPx on screen is twice the viewer's terrain error bound
// (--max-error-px 1.5), what its level of detail may move a ridge; near the
// anchor, where the sight line meets the ground and no screen margin is
// possible, the ground must fall away from the sight line by kNearSlope.
constexpr double kMarginPx = 3;
const double kNearSlope = std::tan(3 * kDeg);

struct SightLine {
  Sight sight = Sight::kUnclear;
  // The most the relief rises above the sight line farther than t_min from
  // the anchor, in pixels across the line of sight (negative: it stays
  // below): hidden from kMarginPx.
  double rise_px = 0;
  // How much of the clearance a visible sight line needs it has at its
  // tightest step (>= 1: visible).
  double clearance = 0;
  double distance = 0;  // eye to anchor, metres
};

// From `cam`'s eye to the ground at lon/lat (the relief's height times k),
// in steps of `step` metres: the relief (times k) at each step's lon/lat against
// the step's height above the ellipsoid. Hidden: the relief rises above
// the sight line by kMarginPx somewhere farther than t_min (2 km and 1 %
// of the distance) from the anchor. Visible: it stays below the sight line
// everywhere by kMarginPx, or, near the anchor, by kNearSlope times the
// distance to it, whichever is less.
SightLine sight_line(const Camera& cam, const Relief& dem, double k, double lon, double lat,
                     double step = 200) {
  SightLine out;
  const Vec3 a = ecef(lon, lat, dem.height(lon, lat) * k);
  const Vec3 d = a - cam.eye;
  const double len = norm(d);
  out.distance = len;
  const Vec3 dir = (1 / len) * d;
  const int n = std::max(32, int(len / step));
  const double t_min = std::max(2000.0, 0.01 * len);
  double rise_px = -1e300, clearance = 1e300;
  for (int i = 1; i < n; ++i) {
    const double s = double(i) / n, u = s * len, t = len - u;
    const Geodetic g = geodetic(cam.eye + u * dir);
    const double rise = dem.height(g.lon, g.lat) * k - g.h;  // metres above the sight line
    const double c = std::abs(dot(dir, up_at(g.lon, g.lat)));
    const double across = std::sqrt(std::max(1e-6, 1 - c * c));  // vertical -> across the ray
    const double px = cam.focal * rise * across / u;
    if (t >= t_min) rise_px = std::max(rise_px, px);
    const double needed = std::min(kMarginPx * u / (cam.focal * across), t * kNearSlope);
    clearance = std::min(clearance, -rise / needed);
  }
  out.rise_px = rise_px;
  out.clearance = clearance;
  out.sight = rise_px >= kMarginPx ? Sight::kHidden
              : clearance >= 1     ? Sight::kVisible
                                   : Sight::kUnclear;
  return out;
}

// ---------------------------------------------------------------------------
// 1. Overlap

TEST(ViewerLabels, NoOverlapOnTheGlobalDisc) {
  const Packages& p = packages();
  TempDir tmp;
  // The disc from six sides, each a view of its own (no path: every label
  // is placed afresh, with its full alpha).
  size_t frames = 0, shown = 0, candidates = 0;
  for (double lon : {-120.0, -60.0, 0.0, 60.0, 120.0, 180.0}) {
    const Pose pose{lon, 20, 20000e3, 0, 0};
    const LabelsJson v = view_labels(p.etopo + " " + p.world + " --camera " + pose_text(pose), 480,
                                     270, tmp.path(), "disc");
    ASSERT_EQ(v.frames.size(), 1u);
    expect_no_overlap(v, "disc at " + pose_text(pose));
    print_rates(v, "disc at " + pose_text(pose));
    ++frames;
    shown += v.frames[0].visible_count();
    candidates += v.frames[0].candidates;
    EXPECT_GE(v.frames[0].visible_count(), 3u) << "too few country names to check";
  }
  std::cout << "global disc: " << shown << " of " << candidates << " candidates shown in " << frames
            << " views\n";
  EXPECT_GE(shown, 40u) << "too few country names to check";
}

TEST(ViewerLabels, NoOverlapObliqueOverEuropeWithAirways) {
  const Packages& p = packages();
  TempDir tmp;
  for (const Pose& pose : {Pose{10, 38, 1200e3, 0, 55}, Pose{15, 42, 600e3, 30, 65}}) {
    const LabelsJson v =
        view_labels(p.etopo + " " + p.world + " " + p.airways + " --camera " + pose_text(pose), 640,
                    360, tmp.path(), "europe");
    ASSERT_EQ(v.frames.size(), 1u);
    expect_no_overlap(v, "Europe at " + pose_text(pose));
    print_rates(v, "Europe at " + pose_text(pose));
    size_t lines = 0, areas = 0;
    for (const Label& l : v.frames[0].labels)
      if (l.visible()) (l.placement == "line" ? lines : areas)++;
    std::cout << "  " << lines << " line labels, " << areas << " others\n";
    EXPECT_GE(lines, 5u) << "too few airway names to check";
  }
}

// ---------------------------------------------------------------------------
// Camera model first: boxes of point labels over zero heights (no terrain),
// where nothing but the camera decides the anchor's pixel. Without charts
// (a heatmap of no opacity): with pies, a label stands beside its pie.

TEST(ViewerLabels, CameraModelAgreesWithPointLabels) {
  const Packages& p = packages();
  TempDir tmp;
  double worst_dy = 0, min_dx = 1e9, max_dx = -1e9;
  size_t n = 0;
  for (const Pose& pose : {Pose{10, 46, 800e3, 0, 0}, Pose{10, 46, 800e3, 20, 30},
                           Pose{12, 44, 500e3, -40, 60}, Pose{10, 52, 1200e3, 180, 45}}) {
    const LabelsJson v = view_labels(
        p.sparse + " --globe --heatmap count --heatmap-opacity 0 --camera " + pose_text(pose), 480,
        270, tmp.path());
    ASSERT_EQ(v.frames.size(), 1u);
    const Camera cam(v.frames[0].pose, v.width, v.height);
    size_t here = 0;
    for (const Label& l : v.frames[0].labels) {
      double x = 0, y = 0;
      ASSERT_TRUE(cam.project(ecef(l.lon, l.lat, 0), x, y)) << l.key();
      const double dx = l.box[0] - x, dy = 0.5 * (l.box[1] + l.box[3]) - y;
      EXPECT_TRUE(dx >= 0 && dx <= 20 && std::abs(dy) <= 3)
          << pose_text(pose) << ": " << describe(l) << ": its anchor projects to " << x << ", " << y
          << " (box left edge " << dx << " px right of it, centre " << dy << " px below)";
      worst_dy = std::max(worst_dy, std::abs(dy));
      min_dx = std::min(min_dx, dx);
      max_dx = std::max(max_dx, dx);
      ++n, ++here;
    }
    EXPECT_GE(here, 5u) << pose_text(pose) << ": too few labels";
  }
  std::cout << n << " point labels: box left edge " << min_dx << " .. " << max_dx
            << " px right of the projected anchor, centre within " << worst_dy << " px\n";
}

// ---------------------------------------------------------------------------
// 2. Occlusion

// The height above the ellipsoid at which lon/lat projects to row y,
// between lo and hi (bisection; NaN when not between them).
double height_at_row(const Camera& cam, double lon, double lat, double y, double lo, double hi) {
  auto row = [&](double h) {
    double px, py;
    return cam.project(ecef(lon, lat, h), px, py) ? py : std::nan("");
  };
  double ylo = row(lo), yhi = row(hi);
  if (!std::isfinite(ylo) || !std::isfinite(yhi) || (ylo - y) * (yhi - y) > 0) return std::nan("");
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (lo + hi), ym = row(mid);
    if (!std::isfinite(ym)) return std::nan("");
    if ((ylo - y) * (ym - y) <= 0)
      hi = mid, yhi = ym;
    else
      lo = mid, ylo = ym;
  }
  return 0.5 * (lo + hi);
}

struct OcclusionCounts {
  size_t in_view = 0, visible = 0, visible_drawn = 0, visible_room_missing = 0, visible_no_room = 0,
         hidden = 0, hidden_drawn = 0, unclear = 0, unclear_drawn = 0;
};

// One view of a grid's points package over etopo20 at exaggeration k:
// each place on screen, its sight line against what the viewer drew.
OcclusionCounts check_occlusion(const std::string& points, const Grid& grid, const Pose& pose,
                                double k, const fs::path& dir) {
  const Packages& p = packages();
  const Relief& dem = etopo_relief();
  OcclusionCounts c;
  const int w = 480, h = 270;
  // Without charts (a heatmap of no opacity): the labels stand beside their
  // anchors, not beside the pies.
  std::ostringstream args;
  args << p.etopo << " " << points << " --camera " << pose_text(pose) << " --exaggeration " << k
       << " --heatmap count --heatmap-opacity 0";
  const LabelsJson v = view_labels(args.str(), w, h, dir, "occlusion");
  if (v.frames.size() != 1) {
    ADD_FAILURE() << "one frame expected";
    return c;
  }
  const Frame& f = v.frames[0];
  const Camera cam(pose, w, h);
  // The drawn point labels' sizes by depth: an absent label's box is
  // estimated from those drawn at a similar depth.
  struct Drawn {
    double depth, w, h;
  };
  std::vector<Drawn> drawn;
  for (const Label& l : f.labels) {
    double x, y, z;
    if (l.visible() && cam.project(ecef(l.lon, l.lat, dem.height(l.lon, l.lat) * k), x, y, &z))
      drawn.push_back({z, l.width(), l.height()});
  }
  struct Disagreement {
    std::string what;
    int x, y;
    double distance;
  };
  std::vector<Disagreement> disagree;
  for (const Place& place : grid_places(grid)) {
    double x, y, z;
    if (!cam.project(ecef(place.lon, place.lat, dem.height(place.lon, place.lat) * k), x, y, &z) ||
        !cam.inside(x, y, 2))
      continue;
    ++c.in_view;
    const SightLine s = sight_line(cam, dem, k, place.lon, place.lat);
    const Label* l = find_label(f, place.name);
    const bool shown = l && l->visible();
    std::ostringstream where;
    where << std::fixed << std::setprecision(1) << place.name << " (" << place.lon << ", "
          << place.lat << ", " << dem.height(place.lon, place.lat) << " m x " << k << ") at pixel "
          << x << ", " << y << ", " << s.distance / 1000 << " km away,";
    std::ostringstream why;
    why << std::fixed << std::setprecision(1);
    if (s.rise_px >= 0)
      why << "the relief rises " << s.rise_px << " px above its sight line";
    else
      why << "the relief stays below its sight line by " << s.clearance << " times the margin, by "
          << -s.rise_px << " px or more beyond " << std::max(2.0, 0.01 * s.distance / 1000)
          << " km from it";
    if (s.sight == Sight::kUnclear) {
      ++c.unclear;
      c.unclear_drawn += shown;
      continue;
    }
    if (s.sight == Sight::kHidden) {
      ++c.hidden;
      if (shown) {
        ++c.hidden_drawn;
        std::ostringstream more;
        // Right of its anchor: the box's middle row is the anchor's row, so
        // the height the viewer's anchor has can be solved for.
        const double cy = 0.5 * (l->box[1] + l->box[3]);
        if (l->box[0] - x >= 0 && l->box[0] - x <= 20) {
          const double hv = height_at_row(cam, place.lon, place.lat, cy, -2000 * k, 9000 * k);
          if (std::isfinite(hv))
            more << std::fixed << std::setprecision(0) << "; its box stands right of the anchor, "
                 << std::setprecision(1) << y - cy << " px higher: an anchor at "
                 << std::setprecision(0) << hv / k << " m x " << k << " instead of "
                 << dem.height(place.lon, place.lat) << " m x " << k;
        }
        ADD_FAILURE() << pose_text(pose) << ": " << where.str() << " is hidden (" << why.str()
                      << "), yet drawn: " << describe(*l) << more.str();
        disagree.push_back({place.name + " hidden, drawn", int(x), int(y), s.distance});
      }
      continue;
    }
    ++c.visible;
    if (shown) {
      ++c.visible_drawn;
      continue;
    }
    // Room: its first place (right of the anchor) on screen and clear of
    // every drawn label by 3 px, at the size of labels drawn at a similar
    // depth (the largest of them).
    double bw = 0, bh = 0;
    for (const Drawn& d : drawn)
      if (d.depth > 0.75 * z && d.depth < 1.33 * z) bw = std::max(bw, d.w), bh = std::max(bh, d.h);
    if (bw == 0)
      for (const Drawn& d : drawn)
        bw = std::max(bw, d.w), bh = std::max(bh, d.h);
    if (bw == 0) bw = 40, bh = 20;
    const std::array<double, 4> box{x + 3, y - bh / 2, x + 3 + bw, y + bh / 2};
    bool room = cam.inside(box[0], box[1], 3) && cam.inside(box[2], box[3], 3);
    for (const Label& o : f.labels)
      if (o.visible() && boxes_intersect(box, o.box, 3)) room = false;
    if (!room) {
      ++c.visible_no_room;
      continue;
    }
    ++c.visible_room_missing;
    ADD_FAILURE() << pose_text(pose) << ": " << where.str() << " is visible (" << why.str()
                  << ") and has room, yet not drawn" << (l ? " (listed with alpha 0)" : "");
    disagree.push_back({place.name + " visible, not drawn", int(x), int(y), s.distance});
  }
  std::cout << "view " << pose_text(pose) << " x" << k << ": " << c.in_view
            << " places on screen; viewer: " << f.visible_count() << " shown of " << f.candidates
            << " candidates, occluded " << f.occluded << ", illegible " << f.illegible
            << "\n  sight lines: " << c.hidden << " hidden (" << c.hidden_drawn << " drawn), "
            << c.visible << " visible (" << c.visible_drawn << " drawn, " << c.visible_no_room
            << " without room, " << c.visible_room_missing << " missing), " << c.unclear
            << " within the margins (" << c.unclear_drawn << " drawn)\n";
  // What the viewer's own picking says is at the disagreeing anchors' pixels.
  if (!disagree.empty()) {
    std::vector<std::pair<int, int>> pixels;
    for (const Disagreement& d : disagree)
      pixels.push_back({d.x, d.y});
    const std::vector<PickAt> picks = view_picks(args.str(), w, h, pixels, dir);
    for (size_t i = 0; i < disagree.size() && i < picks.size(); ++i) {
      std::cout << "  " << disagree[i].what << ": globe-view --pick " << disagree[i].x << ","
                << disagree[i].y << " finds ";
      if (!picks[i].ground) {
        std::cout << "no ground\n";
        continue;
      }
      const double d = norm(ecef(picks[i].lon, picks[i].lat, picks[i].height * k) - cam.eye);
      std::cout << std::fixed << std::setprecision(3) << "ground at " << picks[i].lon << ", "
                << picks[i].lat << std::setprecision(1) << " (" << picks[i].height << " m), "
                << d / 1000 << " km from the eye; the anchor is " << disagree[i].distance / 1000
                << " km away\n";
    }
  }
  return c;
}

void expect_meaningful(const OcclusionCounts& c) {
  EXPECT_GE(c.hidden, 20u) << "the view should hide many places behind the relief";
  EXPECT_GE(c.visible, 10u) << "the view should show many places clearly";
}

TEST(ViewerLabels, TerrainHidesLabelsAcrossTheHimalaya) {
  const Packages& p = packages();
  ASSERT_TRUE(etopo_relief().ok());
  TempDir tmp;
  // From over the Tibetan plateau looking south: the Ganges plain below
  // the range is hidden, the plateau in front is not.
  for (const Pose& pose : {Pose{85, 35, 250e3, 180, 55}, Pose{84, 36, 200e3, 170, 62}}) {
    const OcclusionCounts c = check_occlusion(p.himalaya, kHimalaya, pose, 15, tmp.path());
    expect_meaningful(c);
  }
}

TEST(ViewerLabels, TerrainHidesLabelsAcrossTheAlps) {
  const Packages& p = packages();
  ASSERT_TRUE(etopo_relief().ok());
  TempDir tmp;
  // From Bavaria looking south (the Po plain behind the range) and from
  // the Ligurian Sea looking north (the Swiss plateau behind it).
  for (const Pose& pose : {Pose{10, 48.8, 80e3, 180, 60}, Pose{9, 43.2, 90e3, 10, 60}}) {
    const OcclusionCounts c = check_occlusion(p.alps, kAlps, pose, 20, tmp.path());
    expect_meaningful(c);
  }
}

// ---------------------------------------------------------------------------
// 3. Stability along camera paths

fs::path write_path(const fs::path& dir, const std::vector<Pose>& poses) {
  const fs::path file = dir / "path.txt";
  std::ofstream out(file);
  for (const Pose& p : poses)
    out << pose_text(p) << "\n";
  return file;
}

// Per label (package, label id, text), its alpha in each frame (0 where it
// is not listed); visible where above 0.
std::map<std::string, std::vector<double>> visibility(const LabelsJson& v) {
  std::map<std::string, std::vector<double>> out;
  for (size_t i = 0; i < v.frames.size(); ++i)
    for (const Label& l : v.frames[i].labels) {
      auto& s = out[l.key()];
      s.resize(v.frames.size(), 0);
      s[i] = std::max(0.0, l.alpha);
    }
  return out;
}

// A label's frames as text: '.' hidden, '1'..'9' visible (alpha in ninths).
std::string states(const std::vector<double>& s) {
  std::string out;
  for (double a : s)
    out += a > 0 ? char('0' + std::clamp(int(std::ceil(a * 9)), 1, 9)) : '.';
  return out;
}

// Whether each label's anchor is clearly in view in each frame: on the
// image (2 px inside) and its sight line clear of the relief and of the
// globe's limb (no exaggeration; 5 km steps, a seventh of etopo20's
// grid).
std::map<std::string, std::vector<char>> anchors_in_view(const LabelsJson& v) {
  const Relief& dem = etopo_relief();
  std::map<std::string, std::pair<double, double>> anchors;
  for (const Frame& f : v.frames)
    for (const Label& l : f.labels)
      anchors[l.key()] = {l.lon, l.lat};
  std::map<std::string, std::vector<char>> out;
  for (const auto& [key, ll] : anchors) {
    auto& s = out[key];
    for (const Frame& f : v.frames) {
      const Camera cam(f.pose, v.width, v.height);
      double x, y;
      s.push_back(cam.project(ecef(ll.first, ll.second, dem.height(ll.first, ll.second)), x, y) &&
                  cam.inside(x, y, 2) &&
                  sight_line(cam, dem, 1, ll.first, ll.second, 5000).sight == Sight::kVisible);
    }
  }
  return out;
}

// No state between two others lasts fewer than 3 frames while the anchor
// is in view: a label shown for 1-2 frames is flickering when its anchor
// was in view in the frames before and after (it did not just enter or
// leave the view), a label hidden for 1-2 frames between visible ones
// when its anchor stayed in view through them. Returns the flickering
// labels; `explained` counts the short runs the view explains.
size_t expect_no_flicker(const LabelsJson& v, const std::string& what) {
  const auto seen = visibility(v);
  const auto in_view = anchors_in_view(v);
  size_t bad = 0, explained = 0;
  for (const auto& [key, s] : seen) {
    const std::vector<char>& iv = in_view.at(key);
    size_t start = 0;
    bool first = true, flagged = false;
    for (size_t i = 1; i <= s.size(); ++i) {
      if (i < s.size() && (s[i] > 0) == (s[start] > 0)) continue;
      // A run [start, i): interior when it has neighbours on both sides.
      if (!first && i < s.size() && i - start < 3) {
        bool flicker = true;
        if (s[start] > 0)
          flicker = iv[start - 1] && iv[i];
        else
          for (size_t j = start; j < i; ++j)
            flicker = flicker && iv[j];
        if (!flicker) {
          ++explained;
        } else if (!flagged) {
          flagged = true;
          ++bad;
          std::string view;
          for (char c : iv)
            view += c ? 'v' : '-';
          ADD_FAILURE() << what << ": " << key << " flickers: " << (s[start] > 0 ? "on" : "off")
                        << " for " << i - start << " frame(s) from frame " << start
                        << " while its anchor is in view\n  shown:   " << states(s)
                        << "\n  in view: " << view;
        }
      }
      first = false;
      start = i;
    }
  }
  std::cout << what << ": " << seen.size() << " labels over " << v.frames.size() << " frames, "
            << bad << " flickering; " << explained
            << " short runs where the anchor entered or left the view\n";
  return bad;
}

LabelsJson fly(const std::vector<Pose>& poses, const fs::path& dir) {
  const Packages& p = packages();
  const fs::path file = write_path(dir, poses);
  LabelsJson v = view_labels(p.etopo + " " + p.world + " --camera-path " + file.string(), 480, 270,
                             dir, "path");
  EXPECT_EQ(v.frames.size(), poses.size());
  for (size_t i = 0; i < v.frames.size() && i < poses.size(); ++i)
    EXPECT_NEAR(v.frames[i].pose.height, poses[i].height, 1e-3 * poses[i].height + 1)
        << "frame " << i;
  // Fading labels (0 < alpha < 1) take their room too.
  expect_no_overlap(v, "path");
  return v;
}

TEST(ViewerLabels, StableAlongAPan) {
  ASSERT_TRUE(etopo_relief().ok());
  TempDir tmp;
  std::vector<Pose> poses;
  for (int i = 0; i < 60; ++i)
    poses.push_back({-20 + 0.6 * i, 45, 3000e3, 0, 30});
  const LabelsJson v = fly(poses, tmp.path());
  expect_no_flicker(v, "pan");
}

TEST(ViewerLabels, StableAlongAnOrbit) {
  ASSERT_TRUE(etopo_relief().ok());
  TempDir tmp;
  std::vector<Pose> poses;
  for (int i = 0; i < 60; ++i)
    poses.push_back({10, 47, 2500e3, 6.0 * i, 35});
  const LabelsJson v = fly(poses, tmp.path());
  expect_no_flicker(v, "orbit");
}

TEST(ViewerLabels, StableWhileZoomingIn) {
  ASSERT_TRUE(etopo_relief().ok());
  TempDir tmp;
  std::vector<Pose> poses;
  for (int i = 0; i < 60; ++i)
    poses.push_back({15, 48, 8000e3 * std::pow(0.2, i / 59.0), 0, 20});
  const LabelsJson v = fly(poses, tmp.path());
  ASSERT_EQ(v.frames.size(), poses.size());
  expect_no_flicker(v, "zoom-in");
  // None goes from visible to hidden while its anchor stays clearly in
  // view (on the image and its sight line clear).
  const auto in_view = anchors_in_view(v);
  size_t dropped = 0, left = 0;
  for (const auto& [key, s] : visibility(v))
    for (size_t i = 0; i + 1 < s.size(); ++i) {
      if (!(s[i] > 0) || s[i + 1] > 0) continue;
      if (!in_view.at(key)[i + 1]) {
        ++left;
        continue;
      }
      const Label* l = nullptr;
      for (const Label& c : v.frames[i].labels)
        if (c.key() == key) l = &c;
      const Camera cam(v.frames[i + 1].pose, v.width, v.height);
      double x = 0, y = 0;
      if (l) cam.project(ecef(l->lon, l->lat, etopo_relief().height(l->lon, l->lat)), x, y);
      ++dropped;
      ADD_FAILURE() << std::fixed << std::setprecision(1) << "zoom-in: " << key
                    << " hidden at frame " << i + 1 << " (height "
                    << v.frames[i + 1].pose.height / 1000 << " km) while its anchor ("
                    << (l ? l->lon : 0) << ", " << (l ? l->lat : 0) << ") is in view at " << x
                    << ", " << y << "\n  shown:   " << states(s);
    }
  std::cout << "zoom-in: " << dropped << " labels dropped in view, " << left
            << " hidden as their anchors left the view\n";
}

// ---------------------------------------------------------------------------
// 4. Association and shape

TEST(ViewerLabels, PointLabelsSitBesideTheirAnchors) {
  const Packages& p = packages();
  ASSERT_TRUE(etopo_relief().ok());
  TempDir tmp;
  // US airports over etopo20 (no exaggeration), without charts.
  size_t n = 0;
  std::map<std::string, size_t> sides;
  for (const Pose& pose : {Pose{-95, 30, 2500e3, 0, 40}, Pose{-80, 38, 900e3, 20, 50}}) {
    const LabelsJson v = view_labels(p.etopo + " " + p.airports + " --camera " + pose_text(pose) +
                                         " --heatmap count --heatmap-opacity 0",
                                     640, 360, tmp.path());
    ASSERT_EQ(v.frames.size(), 1u);
    const Camera cam(pose, v.width, v.height);
    size_t here = 0;
    for (const Label& l : v.frames[0].labels) {
      if (!l.visible() || l.placement != "point") continue;
      double x, y;
      ASSERT_TRUE(cam.project(ecef(l.lon, l.lat, etopo_relief().height(l.lon, l.lat)), x, y));
      // Beside: on one side of the anchor, 0..20 px away from it along that
      // side's axis and centred on it within 4 px across.
      const double cx = 0.5 * (l.box[0] + l.box[2]), cy = 0.5 * (l.box[1] + l.box[3]);
      auto near = [](double gap, double off) {
        return gap >= -1 && gap <= 20 && std::abs(off) <= 4;
      };
      const char* side = near(l.box[0] - x, cy - y)   ? "right"
                         : near(x - l.box[2], cy - y) ? "left"
                         : near(y - l.box[3], cx - x) ? "above"
                         : near(l.box[1] - y, cx - x) ? "below"
                                                      : nullptr;
      EXPECT_TRUE(side) << pose_text(pose) << ": " << describe(l) << " is not beside its anchor at "
                        << x << ", " << y;
      sides[side ? side : "nowhere"]++;
      ++n, ++here;
    }
    EXPECT_GE(here, 10u) << pose_text(pose) << ": too few airport names to check";
  }
  std::cout << n << " point labels:";
  for (const auto& [side, count] : sides)
    std::cout << " " << count << " " << side;
  std::cout << "\n";
}

// Distance from (x, y) to the segment a-b.
double segment_distance(double x, double y, double ax, double ay, double bx, double by) {
  const double dx = bx - ax, dy = by - ay, len2 = dx * dx + dy * dy;
  const double t = len2 > 0 ? std::clamp(((x - ax) * dx + (y - ay) * dy) / len2, 0.0, 1.0) : 0;
  return std::hypot(x - ax - t * dx, y - ay - t * dy);
}

// Each visible line label of `package` in the view: glyph centres on the
// projected path (densified to 1 km, draped at the relief's heights),
// neighbouring glyph angles within 45 degrees, every angle upright.
void check_line_labels(const std::string& args, const std::string& package, const Pose& pose,
                       const fs::path& dir, size_t min_labels) {
  const Relief& dem = etopo_relief();
  const LabelsJson v = view_labels(args + " --camera " + pose_text(pose), 640, 360, dir, "lines");
  ASSERT_EQ(v.frames.size(), 1u);
  const auto paths = label_paths(package);
  const Camera cam(pose, v.width, v.height);
  const std::string name = fs::path(package).filename().string();
  size_t labels = 0, glyphs = 0, off_line = 0, turns = 0, upside_down = 0, unwrapped = 0;
  double worst = 0, worst_turn = 0;
  for (const Label& l : v.frames[0].labels) {
    if (!l.visible() || l.placement != "line") continue;
    EXPECT_EQ(fs::path(l.package).filename().string(), name) << describe(l);
    EXPECT_GE(l.glyphs.size(), 1u) << describe(l) << ": a line label without glyphs";
    const auto it = paths.find(l.id);
    if (it == paths.end() || it->second.size() < 2) {
      ADD_FAILURE() << describe(l) << ": no path in the package's labels table";
      continue;
    }
    ++labels;
    std::vector<std::array<double, 2>> screen;
    for (size_t i = 0; i + 1 < it->second.size(); ++i) {
      const auto& a = it->second[i];
      const auto& b = it->second[i + 1];
      const int steps = std::max(1, int(haversine_m(a[0], a[1], b[0], b[1]) / 1000));
      for (int s = 0; s <= steps; ++s) {
        const double lon = a[0] + (b[0] - a[0]) * s / steps, lat = a[1] + (b[1] - a[1]) * s / steps;
        double x, y;
        if (cam.project(ecef(lon, lat, std::max(0.0, dem.height(lon, lat))), x, y))
          screen.push_back({x, y});
      }
    }
    const double tolerance = 0.5 * text_height(l);
    for (size_t g = 0; g < l.glyphs.size(); ++g) {
      const Glyph& gl = l.glyphs[g];
      double d = 1e300;
      for (size_t i = 0; i + 1 < screen.size(); ++i)
        d = std::min(d, segment_distance(gl.x, gl.y, screen[i][0], screen[i][1], screen[i + 1][0],
                                         screen[i + 1][1]));
      ++glyphs;
      worst = std::max(worst, d);
      if (d > tolerance) {
        if (++off_line <= 10)
          ADD_FAILURE() << std::fixed << std::setprecision(1) << describe(l) << ": glyph " << g
                        << " at " << gl.x << ", " << gl.y << " is " << d
                        << " px from its line (half the text height: " << tolerance << ")";
      }
      // Angles are clockwise from the +x axis, pixels y down (the direction
      // from one glyph to the next); 330 is -30.
      const double a = std::remainder(gl.angle, 360.0);
      unwrapped += gl.angle <= -180 || gl.angle > 180;
      if (std::abs(a) > 90 + 1e-6) {
        if (++upside_down <= 10)
          ADD_FAILURE() << std::fixed << std::setprecision(1) << describe(l) << ": glyph " << g
                        << " at " << gl.x << ", " << gl.y << " is upside down: " << gl.angle
                        << " degrees";
      }
      if (g + 1 < l.glyphs.size()) {
        const Glyph& next = l.glyphs[g + 1];
        const double dir = std::atan2(next.y - gl.y, next.x - gl.x) / kDeg;
        EXPECT_LE(std::abs(std::remainder(dir - gl.angle, 360.0)), 45)
            << describe(l) << ": glyph " << g << "'s angle " << gl.angle
            << " is not the way to the next glyph (" << dir << " degrees)";
      }
      if (g > 0) {
        const double turn = std::abs(std::remainder(gl.angle - l.glyphs[g - 1].angle, 360.0));
        worst_turn = std::max(worst_turn, turn);
        if (turn > 45) {
          if (++turns <= 10)
            ADD_FAILURE() << describe(l) << ": glyphs " << g - 1 << " and " << g << " turn by "
                          << turn << " degrees";
        }
      }
    }
  }
  std::cout << name << " at " << pose_text(pose) << ": " << labels << " line labels, " << glyphs
            << " glyphs; farthest from its line " << worst << " px, sharpest turn " << worst_turn
            << " degrees; " << off_line << " off the line, " << turns << " turns over 45, "
            << upside_down << " upside down; " << unwrapped
            << " angles written outside -180..180\n";
  EXPECT_GE(labels, min_labels) << "too few line labels to check";
}

TEST(ViewerLabels, LineLabelsFollowTheirLines) {
  const Packages& p = packages();
  ASSERT_TRUE(etopo_relief().ok());
  TempDir tmp;
  check_line_labels(p.etopo + " " + p.airways, p.airways, {10, 38, 1200e3, 0, 55}, tmp.path(), 10);
  check_line_labels(p.etopo + " " + p.curves, p.curves, {10, 36, 1500e3, 0, 45}, tmp.path(), 3);
  // Looking east along the curves: they wind up the screen, through the
  // vertical.
  check_line_labels(p.etopo + " " + p.curves, p.curves, {0, 47, 700e3, 90, 55}, tmp.path(), 3);
}

}  // namespace
