// `globe-vectorize areas` (polygons cut into tiles) tested black-box, as users
// run it: through the command line (areas, info, validate, export, extract)
// and with GDAL/OGR as the reader and the reference. GDAL's MVT driver decodes
// the exported tiles, OGR reads the source GeoPackages and reprojects them,
// GEOS (OGR_G_IsValid) judges validity; point-in-polygon, distances to borders
// and R's quantile type 7 are brute force written here. Nothing of the tool's
// own polygon or tile code is used.
//
// Samples: samples/data/world.gpkg (177 countries, EPSG:4326; Antarctica down
// to -89.9, Fiji and Russia cut at +-180) and samples/data/nc.gpkg (the 100
// North Carolina counties, NAD27, neighbours sharing their borders vertex for
// vertex), from samples/fetch.sh; the tests skip without them.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <memory>
#include <numbers>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include <gdal.h>
#include <ogr_api.h>
#include <ogr_srs_api.h>

#include "package_compare.hpp"
#include "raster_fixtures.hpp"
#include "test_support.hpp"
#include "tileformat/json.hpp"

using namespace globe_test;

namespace {

using tileformat::JsonValue;

constexpr double kR = 6378137.0;                    // web mercator sphere
constexpr double kHalf = kR * std::numbers::pi;     // 20037508.34 m
constexpr double kCutX = kHalf * (179.9999 / 180);  // beyond: a +-180 cut

double merc_x(double lon) {
  return kR * lon * std::numbers::pi / 180;
}
double merc_y(double lat) {
  return kR * std::log(std::tan(std::numbers::pi / 4 + lat * std::numbers::pi / 360));
}
double lon_of(double x) {
  return x / kR * 180 / std::numbers::pi;
}
double lat_of(double y) {
  return std::atan(std::sinh(y / kR)) * 180 / std::numbers::pi;
}
double tile_m(int z) {
  return 2 * kHalf / double(1 << z);
}
// One pixel of zoom z (a tile is 256 px), in web mercator metres.
double px_m(int z) {
  return tile_m(z) / 256;
}

struct P {
  double x = 0, y = 0;
};

struct Ring {
  std::vector<P> pts;  // closed (last == first) as OGR gives them
  bool outer = false;  // the first ring of its polygon
  double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
};

// A (multi)polygon as its rings, for even-odd point-in-polygon and distances
// to its edges (brute force, each ring culled by its box).
struct Shape {
  std::vector<Ring> rings;
  double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;

  bool contains(P p) const {
    if (p.x < x0 || p.x > x1 || p.y < y0 || p.y > y1) return false;
    bool in = false;
    for (const Ring& r : rings) {
      if (p.x < r.x0 || p.x > r.x1 || p.y < r.y0 || p.y > r.y1) continue;
      const size_t n = r.pts.size();
      for (size_t i = 0, j = n - 1; i < n; j = i++) {
        const P a = r.pts[i], b = r.pts[j];
        if ((a.y > p.y) != (b.y > p.y) && p.x < (b.x - a.x) * (p.y - a.y) / (b.y - a.y) + a.x)
          in = !in;
      }
    }
    return in;
  }
  // Whether an edge lies within d of p; edges along the antimeridian (both
  // ends beyond kCutX on one side) are cuts of the data, not borders.
  bool near(P p, double d) const {
    if (p.x < x0 - d || p.x > x1 + d || p.y < y0 - d || p.y > y1 + d) return false;
    const double d2 = d * d;
    for (const Ring& r : rings) {
      if (p.x < r.x0 - d || p.x > r.x1 + d || p.y < r.y0 - d || p.y > r.y1 + d) continue;
      for (size_t i = 0; i + 1 < r.pts.size(); ++i) {
        const P a = r.pts[i], b = r.pts[i + 1];
        if ((a.x > kCutX && b.x > kCutX) || (a.x < -kCutX && b.x < -kCutX)) continue;
        if (std::max(a.x, b.x) < p.x - d || std::min(a.x, b.x) > p.x + d ||
            std::max(a.y, b.y) < p.y - d || std::min(a.y, b.y) > p.y + d)
          continue;
        const double dx = b.x - a.x, dy = b.y - a.y, len2 = dx * dx + dy * dy;
        const double t =
            len2 > 0 ? std::clamp(((p.x - a.x) * dx + (p.y - a.y) * dy) / len2, 0.0, 1.0) : 0.0;
        const double ex = p.x - a.x - t * dx, ey = p.y - a.y - t * dy;
        if (ex * ex + ey * ey <= d2) return true;
      }
    }
    return false;
  }
};

double signed_area(const Ring& r) {
  double a = 0;
  for (size_t i = 0; i + 1 < r.pts.size(); ++i)
    a += r.pts[i].x * r.pts[i + 1].y - r.pts[i + 1].x * r.pts[i].y;
  return a / 2;
}

void add_rings(OGRGeometryH g, Shape& s) {
  const OGRwkbGeometryType t = wkbFlatten(OGR_G_GetGeometryType(g));
  if (t == wkbPolygon) {
    for (int i = 0; i < OGR_G_GetGeometryCount(g); ++i) {
      OGRGeometryH ring = OGR_G_GetGeometryRef(g, i);
      Ring r;
      r.outer = i == 0;
      const int n = OGR_G_GetPointCount(ring);
      for (int k = 0; k < n; ++k) {
        const P p{OGR_G_GetX(ring, k), OGR_G_GetY(ring, k)};
        r.pts.push_back(p);
        r.x0 = std::min(r.x0, p.x), r.x1 = std::max(r.x1, p.x);
        r.y0 = std::min(r.y0, p.y), r.y1 = std::max(r.y1, p.y);
      }
      if (r.pts.size() < 2) continue;
      s.x0 = std::min(s.x0, r.x0), s.x1 = std::max(s.x1, r.x1);
      s.y0 = std::min(s.y0, r.y0), s.y1 = std::max(s.y1, r.y1);
      s.rings.push_back(std::move(r));
    }
  } else if (t == wkbMultiPolygon || t == wkbGeometryCollection) {
    for (int i = 0; i < OGR_G_GetGeometryCount(g); ++i)
      add_rings(OGR_G_GetGeometryRef(g, i), s);
  }
}

std::string wkt_start(OGRGeometryH g, size_t chars = 300) {
  char* w = nullptr;
  OGR_G_ExportToWkt(g, &w);
  std::string s = w ? w : "";
  CPLFree(w);
  return s.size() > chars ? s.substr(0, chars) + "..." : s;
}

// The first problems of a kind, and how many there were.
struct Problems {
  size_t count = 0;
  std::string first;
  void add(const std::string& what) {
    if (++count <= 12) first += "  " + what + "\n";
  }
  std::string text() const { return std::to_string(count) + " problem(s), the first:\n" + first; }
};

// ---------------------------------------------------------------------------
// The source, read by OGR and reprojected to web mercator.

struct SourceFeature {
  std::string key;                    // the attribute naming it (name_long, NAME)
  std::map<std::string, double> num;  // numeric fields set and not null
  Shape merc;                         // EPSG:3857 (vertices reprojected)
};

OGRSpatialReferenceH srs_from(const char* user_input) {
  OGRSpatialReferenceH s = OSRNewSpatialReference(nullptr);
  OSRSetFromUserInput(s, user_input);
  OSRSetAxisMappingStrategy(s, OAMS_TRADITIONAL_GIS_ORDER);
  return s;
}

std::vector<SourceFeature> read_source(const fs::path& path, const std::string& key_field) {
  gdal_setup();
  std::vector<SourceFeature> out;
  GDALDatasetH ds = GDALOpenEx(path.c_str(), GDAL_OF_VECTOR, nullptr, nullptr, nullptr);
  if (!ds) {
    ADD_FAILURE() << "OGR cannot open " << path;
    return out;
  }
  OGRLayerH layer = GDALDatasetGetLayer(ds, 0);
  OGRSpatialReferenceH from = OSRClone(OGR_L_GetSpatialRef(layer));
  OSRSetAxisMappingStrategy(from, OAMS_TRADITIONAL_GIS_ORDER);
  OGRSpatialReferenceH to = srs_from("EPSG:3857");
  OGRCoordinateTransformationH ct = OCTNewCoordinateTransformation(from, to);
  OGR_L_ResetReading(layer);
  while (OGRFeatureH f = OGR_L_GetNextFeature(layer)) {
    SourceFeature s;
    OGRFeatureDefnH defn = OGR_F_GetDefnRef(f);
    for (int i = 0; i < OGR_FD_GetFieldCount(defn); ++i) {
      OGRFieldDefnH fd = OGR_FD_GetFieldDefn(defn, i);
      if (!OGR_F_IsFieldSetAndNotNull(f, i)) continue;
      const std::string name = OGR_Fld_GetNameRef(fd);
      if (name == key_field) s.key = OGR_F_GetFieldAsString(f, i);
      const OGRFieldType t = OGR_Fld_GetType(fd);
      if (t == OFTReal || t == OFTInteger || t == OFTInteger64)
        s.num[name] = OGR_F_GetFieldAsDouble(f, i);
    }
    if (OGRGeometryH g = OGR_F_GetGeometryRef(f)) {
      OGRGeometryH m = OGR_G_Clone(g);
      if (OGR_G_Transform(m, ct) != OGRERR_NONE)
        ADD_FAILURE() << s.key << ": OGR cannot reproject it to EPSG:3857";
      add_rings(m, s.merc);
      OGR_G_DestroyGeometry(m);
    }
    out.push_back(std::move(s));
    OGR_F_Destroy(f);
  }
  OCTDestroyCoordinateTransformation(ct);
  OSRRelease(from);
  OSRRelease(to);
  GDALClose(ds);
  return out;
}

// ---------------------------------------------------------------------------
// Exported tiles, read by GDAL's MVT driver (each tile its own dataset,
// georeferenced in EPSG:3857 by X/Y/Z, unclipped: what the tile holds).

struct Decoded {
  std::string layer;
  std::map<std::string, std::string> fields;  // mvt_id and the tags, as text
  OGRwkbGeometryType type = wkbUnknown;
  bool valid = false;
  std::string wkt;  // the start of it, where invalid
  Shape shape;
  std::string key(const std::string& field) const {
    const auto it = fields.find(field);
    return it == fields.end() ? "" : it->second;
  }
};

struct TileKey {
  int z, x, y;
  bool operator<(const TileKey& o) const { return std::tie(z, x, y) < std::tie(o.z, o.x, o.y); }
  std::string str() const {
    return std::to_string(z) + "/" + std::to_string(x) + "/" + std::to_string(y);
  }
};

std::vector<Decoded> read_tile(const fs::path& pbf, int z, int x, int y, bool& opened) {
  gdal_setup();
  const std::string ox = "X=" + std::to_string(x), oy = "Y=" + std::to_string(y),
                    oz = "Z=" + std::to_string(z);
  const char* opts[] = {ox.c_str(), oy.c_str(), oz.c_str(), "CLIP=NO", "METADATA_FILE=", nullptr};
  const char* drivers[] = {"MVT", nullptr};
  std::vector<Decoded> out;
  GDALDatasetH ds = GDALOpenEx(pbf.c_str(), GDAL_OF_VECTOR, drivers, opts, nullptr);
  opened = ds != nullptr;
  if (!ds) return out;
  for (int l = 0; l < GDALDatasetGetLayerCount(ds); ++l) {
    OGRLayerH layer = GDALDatasetGetLayer(ds, l);
    OGR_L_ResetReading(layer);
    while (OGRFeatureH f = OGR_L_GetNextFeature(layer)) {
      Decoded d;
      d.layer = OGR_L_GetName(layer);
      OGRFeatureDefnH defn = OGR_F_GetDefnRef(f);
      for (int i = 0; i < OGR_FD_GetFieldCount(defn); ++i)
        if (OGR_F_IsFieldSetAndNotNull(f, i))
          d.fields[OGR_Fld_GetNameRef(OGR_FD_GetFieldDefn(defn, i))] = OGR_F_GetFieldAsString(f, i);
      if (OGRGeometryH g = OGR_F_GetGeometryRef(f)) {
        d.type = wkbFlatten(OGR_G_GetGeometryType(g));
        d.valid = OGR_G_IsValid(g);
        if (!d.valid) d.wkt = wkt_start(g);
        add_rings(g, d.shape);
      }
      out.push_back(std::move(d));
      OGR_F_Destroy(f);
    }
  }
  GDALClose(ds);
  return out;
}

using Tiles = std::map<TileKey, std::vector<Decoded>>;

// Every tile of zoom z in an exported folder (DIR/z/x/y.pbf).
Tiles read_zoom(const fs::path& mvt, int z, Problems* unreadable = nullptr) {
  Tiles tiles;
  const fs::path zdir = mvt / std::to_string(z);
  if (!fs::is_directory(zdir)) return tiles;
  for (const auto& e : fs::recursive_directory_iterator(zdir)) {
    if (e.path().extension() != ".pbf") continue;
    const TileKey k{z, std::stoi(e.path().parent_path().filename().string()),
                    std::stoi(e.path().stem().string())};
    bool opened = false;
    tiles[k] = read_tile(e.path(), k.z, k.x, k.y, opened);
    if (!opened && unreadable) unreadable->add(k.str() + ": GDAL's MVT driver cannot open it");
  }
  return tiles;
}

TileKey tile_of(P p, int z) {
  const int n = 1 << z;
  return {z, std::clamp(int(std::floor((p.x + kHalf) / tile_m(z))), 0, n - 1),
          std::clamp(int(std::floor((kHalf - p.y) / tile_m(z))), 0, n - 1)};
}

// The decoded features of p's tile that contain p.
std::vector<const Decoded*> covering(const Tiles& tiles, P p, int z) {
  std::vector<const Decoded*> out;
  const auto it = tiles.find(tile_of(p, z));
  if (it == tiles.end()) return out;
  for (const Decoded& d : it->second)
    if (d.shape.contains(p)) out.push_back(&d);
  return out;
}

std::string names(const std::vector<const Decoded*>& ds, const std::string& key_field) {
  std::string s;
  for (const Decoded* d : ds)
    s += (s.empty() ? "" : ", ") + d->key(key_field);
  return "[" + s + "]";
}

std::string where(P p, int z) {
  std::ostringstream s;
  s.precision(8);
  s << "lon " << lon_of(p.x) << " lat " << lat_of(p.y) << " (tile " << tile_of(p, z).str() << ")";
  return s.str();
}

// ---------------------------------------------------------------------------
// Packages built once per build tree (test_support.hpp shared_folder).

// A number as text that reads back the same.
std::string g17(double v) {
  char b[40];
  std::snprintf(b, sizeof b, "%.17g", v);
  return b;
}

// A member that is a number, or NaN (a failure to compare).
double number(const JsonValue& o, const char* key) {
  const JsonValue* v = o.find(key);
  if (!v || !v->is_number()) {
    ADD_FAILURE() << "no number " << key << " in " << o.text();
    return std::nan("");
  }
  return v->number();
}

bool have_samples(std::initializer_list<const char*> names) {
  for (const char* n : names)
    if (!fs::exists(samples() / n)) return false;
  return true;
}

// `areas OPTIONS SRC -o DIR/NAME.mbtiles`, then `export` to DIR/mvt (and
// DIR/style.json); returns the folder, empty when a step failed (a test
// failure with the command's stderr).
fs::path built(const std::string& name, const std::string& source, const std::string& options) {
  const fs::path dir = shared_folder("areas-" + name, [&](const fs::path& d) {
    const std::string pkg = (d / (name + ".mbtiles")).string();
    return run_all(
        {vectorize() + " areas -q " + (samples() / source).string() + " " + options + " -o " + pkg,
         vectorize() + " export -q " + pkg + " -o " + (d / "mvt").string() + " --style-json " +
             (d / "style.json").string()},
        d);
  });
  if (!fs::exists(dir / ".stamp")) return {};
  return dir;
}

const char* kWhereAntimeridian =
    "--where \"name_long IN ('Fiji','Russian Federation','Antarctica')\"";

fs::path world() {
  return built("world", "world.gpkg", "--max-zoom 4");
}
fs::path nc() {
  return built("nc", "nc.gpkg", "--max-zoom 9");
}

}  // namespace

// Every tile of every zoom of the world (0-4) and of North Carolina (0-9) is
// a gzipped MVT that GDAL's driver opens; its features lie in one layer named
// as the source layer, carry an id and the source attributes, are polygons or
// multipolygons that GEOS finds valid, and wind as MVT 2.1 says (exterior
// rings clockwise in tile coordinates, y down: counter-clockwise once GDAL
// has turned y up). `validate` accepts both packages, `info --json` calls
// them areas.
TEST(AreasMvt, GdalReadsEveryTileAndEveryPolygonIsValid) {
  if (!have_samples({"world.gpkg", "nc.gpkg"}))
    GTEST_SKIP() << "samples/data/world.gpkg or nc.gpkg missing: run samples/fetch.sh";
  struct Case {
    fs::path dir;
    std::string name, layer, key;
    int max_zoom;
  };
  const fs::path w = world();
  ASSERT_FALSE(w.empty()) << "building the world package failed (above)";
  const fs::path n = nc();
  ASSERT_FALSE(n.empty()) << "building the North Carolina package failed (above)";
  for (const Case& c :
       {Case{w, "world", "world", "name_long", 4}, Case{n, "nc", "nc.gpkg", "NAME", 9}}) {
    SCOPED_TRACE(c.name);
    TempDir scratch(c.name);
    const std::string pkg = (c.dir / (c.name + ".mbtiles")).string();
    const RunResult v = run(vectorize() + " validate " + pkg, scratch.path());
    EXPECT_EQ(v.exit_code, 0) << v.out << v.err;
    const RunResult info = run(vectorize() + " info " + pkg + " --json", scratch.path());
    ASSERT_EQ(info.exit_code, 0) << info.err;
    const JsonValue j = JsonValue::parse(info.out);
    ASSERT_NE(j.find("kind"), nullptr) << info.out;
    EXPECT_EQ(j.find("kind")->string(), "areas");
    ASSERT_NE(j.find("areas"), nullptr) << info.out;
    EXPECT_TRUE(j.find("areas")->is_object()) << info.out;

    size_t features = 0, tiles = 0;
    Problems p;
    std::set<std::string> keys;
    for (int z = 0; z <= c.max_zoom; ++z) {
      const Tiles zoom = read_zoom(c.dir / "mvt", z, &p);
      if (zoom.empty()) p.add("zoom " + std::to_string(z) + ": no tile exported");
      for (const auto& [k, fs_] : zoom) {
        ++tiles;
        const std::string bytes = read_file(c.dir / "mvt" / (k.str() + ".pbf"));
        if (bytes.size() < 2 || uint8_t(bytes[0]) != 0x1f || uint8_t(bytes[1]) != 0x8b)
          p.add(k.str() + ": not gzip-compressed");
        if (fs_.empty()) p.add(k.str() + ": a tile without a feature GDAL reads");
        for (const Decoded& d : fs_) {
          ++features;
          const std::string id =
              k.str() + " feature " + d.key("mvt_id") + " (" + d.key(c.key) + ")";
          if (d.layer != c.layer) p.add(id + ": layer '" + d.layer + "', not '" + c.layer + "'");
          if (!d.fields.count("mvt_id")) p.add(id + ": no feature id");
          if (d.key(c.key).empty()) p.add(id + ": no " + c.key + " tag");
          keys.insert(d.key(c.key));
          if (d.type != wkbPolygon && d.type != wkbMultiPolygon) {
            p.add(id + ": geometry type " + OGRGeometryTypeToName(d.type));
            continue;
          }
          if (!d.valid) p.add(id + ": invalid (GEOS): " + d.wkt);
          for (size_t r = 0; r < d.shape.rings.size(); ++r) {
            const double a = signed_area(d.shape.rings[r]);
            // Positive area in tile coordinates (y down) is negative once y is up.
            if (d.shape.rings[r].outer ? a >= 0 : a <= 0)
              p.add(id + ": ring " + std::to_string(r) +
                    (d.shape.rings[r].outer ? " (exterior)" : " (hole)") +
                    " winds the wrong way (area " + std::to_string(a) + " m2, y up)");
          }
        }
      }
    }
    EXPECT_EQ(p.count, 0u) << p.text();
    EXPECT_GT(tiles, size_t(c.max_zoom));
    EXPECT_GE(features, tiles);
    // Every source feature shows somewhere (the world's at zoom 0-4 too).
    const auto source = read_source(samples() / (c.name + ".gpkg"), c.key);
    size_t missing = 0;
    std::string missing_names;
    for (const SourceFeature& s : source)
      if (!keys.count(s.key)) ++missing, missing_names += " " + s.key;
    EXPECT_EQ(missing, 0u) << "source features in no tile:" << missing_names;
  }
}

// Random points (fixed seed) in every tile of the finest zoom (world 4: all
// 256 tiles, written or not; North Carolina 9: the tiles over the state):
// which feature contains each, in the decoded tile (by its name tag) and in
// the source (OGR's reading reprojected to web mercator). Points farther than
// 1.5 px of that zoom from every source border must agree, 99.9 % of them.
TEST(AreasMvt, PointInPolygonAgreesWithTheSource) {
  if (!have_samples({"world.gpkg", "nc.gpkg"}))
    GTEST_SKIP() << "samples/data/world.gpkg or nc.gpkg missing: run samples/fetch.sh";
  struct Case {
    fs::path dir;
    std::string name, key;
    int z, per_tile;
  };
  const fs::path w = world();
  ASSERT_FALSE(w.empty()) << "building the world package failed (above)";
  const fs::path n = nc();
  ASSERT_FALSE(n.empty()) << "building the North Carolina package failed (above)";
  // The finest zooms, and the world's coarse ones too: a ring that clipping
  // turned inside out there covers the ocean (found at zoom 1).
  for (const Case& c :
       {Case{w, "world", "name_long", 4, 30}, Case{n, "nc", "NAME", 9, 60},
        Case{w, "world", "name_long", 0, 3000}, Case{w, "world", "name_long", 1, 800},
        Case{w, "world", "name_long", 2, 250}}) {
    SCOPED_TRACE(c.name + " zoom " + std::to_string(c.z));
    const auto source = read_source(samples() / (c.name + ".gpkg"), c.key);
    ASSERT_FALSE(source.empty());
    double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
    for (const SourceFeature& s : source)
      x0 = std::min(x0, s.merc.x0), x1 = std::max(x1, s.merc.x1), y0 = std::min(y0, s.merc.y0),
      y1 = std::max(y1, s.merc.y1);
    const TileKey a = tile_of({x0, y1}, c.z), b = tile_of({x1, y0}, c.z);
    const Tiles tiles = read_zoom(c.dir / "mvt", c.z);
    ASSERT_FALSE(tiles.empty()) << "no tile of zoom " << c.z;
    const double margin = 1.5 * px_m(c.z), t = tile_m(c.z);
    std::mt19937 rng(20240601);
    std::uniform_real_distribution<double> u(0, 1);
    size_t checked = 0, agree = 0, inside = 0;
    Problems p;
    for (int ty = a.y; ty <= b.y; ++ty)
      for (int tx = a.x; tx <= b.x; ++tx)
        for (int k = 0; k < c.per_tile; ++k) {
          const P pt{-kHalf + (tx + u(rng)) * t, kHalf - (ty + u(rng)) * t};
          std::string want;
          bool near = false;
          for (const SourceFeature& s : source) {
            if (s.merc.near(pt, margin)) near = true;
            if (want.empty() && s.merc.contains(pt)) want = s.key;
          }
          if (near) continue;
          ++checked;
          inside += !want.empty();
          const auto got = covering(tiles, pt, c.z);
          const std::string have = got.empty() ? "" : got.front()->key(c.key);
          if (have == want && got.size() <= 1) {
            ++agree;
          } else {
            p.add(where(pt, c.z) + ": source " + (want.empty() ? "none" : want) + ", tiles " +
                  names(got, c.key));
          }
        }
    EXPECT_GT(checked, size_t(1000));
    EXPECT_GT(inside, checked / 10) << "few points fell inside the polygons";
    EXPECT_GE(double(agree), 0.999 * double(checked))
        << agree << " of " << checked << " points agree; " << p.text();
  }
}

// North Carolina's counties share their borders exactly; so must their tiles,
// at every zoom from 5 to 9. Points are taken along every shared border
// (spaced along it, offset across it): within 1 px of it, each point inside
// the state and farther than 1.5 px from the state's outer boundary is
// covered by a decoded polygon (no gap); 1.5 and 3 px off it, each point
// farther than 1 px from every border is covered by exactly one (no overlap).
TEST(AreasMvt, NeighboursShareTheirBorderAtEveryZoom) {
  if (!have_samples({"nc.gpkg"})) GTEST_SKIP() << "samples/data/nc.gpkg missing";
  const fs::path n = nc();
  ASSERT_FALSE(n.empty()) << "building the North Carolina package failed (above)";
  const auto source = read_source(samples() / "nc.gpkg", "NAME");
  ASSERT_EQ(source.size(), 100u);
  // Shared edges: the same two vertices in two counties' rings.
  std::map<std::array<double, 4>, int> edges;
  auto key = [](P a, P b) {
    if (std::tie(b.x, b.y) < std::tie(a.x, a.y)) std::swap(a, b);
    return std::array<double, 4>{a.x, a.y, b.x, b.y};
  };
  for (const SourceFeature& s : source)
    for (const Ring& r : s.merc.rings)
      for (size_t i = 0; i + 1 < r.pts.size(); ++i)
        ++edges[key(r.pts[i], r.pts[i + 1])];
  Shape outer;  // the state's outer boundary: edges of one county only
  std::vector<std::pair<P, P>> shared;
  double shared_len = 0;
  for (const auto& [k, count] : edges) {
    const P a{k[0], k[1]}, b{k[2], k[3]};
    if (count >= 2) {
      shared.emplace_back(a, b);
      shared_len += std::hypot(b.x - a.x, b.y - a.y);
    } else {
      Ring r;
      r.pts = {a, b};
      r.x0 = std::min(a.x, b.x), r.x1 = std::max(a.x, b.x);
      r.y0 = std::min(a.y, b.y), r.y1 = std::max(a.y, b.y);
      outer.x0 = std::min(outer.x0, r.x0), outer.x1 = std::max(outer.x1, r.x1);
      outer.y0 = std::min(outer.y0, r.y0), outer.y1 = std::max(outer.y1, r.y1);
      outer.rings.push_back(r);
    }
  }
  ASSERT_GT(shared.size(), edges.size() / 3) << "nc.gpkg's counties share few edges exactly";
  auto in_state = [&](P p) {
    for (const SourceFeature& s : source)
      if (s.merc.contains(p)) return true;
    return false;
  };
  auto near_border = [&](P p, double d) {
    for (const SourceFeature& s : source)
      if (s.merc.near(p, d)) return true;
    return false;
  };
  for (int z = 5; z <= 9; ++z) {
    SCOPED_TRACE("zoom " + std::to_string(z));
    const Tiles tiles = read_zoom(n / "mvt", z);
    ASSERT_FALSE(tiles.empty());
    const double px = px_m(z), step = std::max(2 * px, shared_len / 2500);
    size_t gap_checked = 0, overlap_checked = 0;
    Problems gaps, overlaps;
    double phase = 0;  // arc length to the next position, carried along
    for (const auto& [a, b] : shared) {
      const double len = std::hypot(b.x - a.x, b.y - a.y);
      const double nx = -(b.y - a.y) / len, ny = (b.x - a.x) / len;
      for (double s = phase; s < len; s += step) {
        const P on{a.x + (b.x - a.x) * s / len, a.y + (b.y - a.y) * s / len};
        for (double side : {-1.0, 1.0}) {
          for (double off : {0.25, 0.5, 1.0}) {
            const P pt{on.x + side * off * px * nx, on.y + side * off * px * ny};
            if (!in_state(pt) || outer.near(pt, 1.5 * px)) continue;
            ++gap_checked;
            if (covering(tiles, pt, z).empty())
              gaps.add(where(pt, z) + ": " + std::to_string(off) +
                       " px off a shared border, in no polygon");
          }
          for (double off : {1.5, 3.0}) {
            const P pt{on.x + side * off * px * nx, on.y + side * off * px * ny};
            if (!in_state(pt) || near_border(pt, px)) continue;
            ++overlap_checked;
            const auto got = covering(tiles, pt, z);
            if (got.size() != 1)
              overlaps.add(where(pt, z) + ": " + std::to_string(off) +
                           " px off a shared border, in " + std::to_string(got.size()) +
                           " polygons " + names(got, "NAME"));
          }
        }
      }
      phase = std::fmod(phase - len, step);
      if (phase < 0) phase += step;
    }
    EXPECT_GT(gap_checked, size_t(500));
    EXPECT_GT(overlap_checked, size_t(200));
    EXPECT_EQ(gaps.count, 0u) << "gaps along shared borders, of " << gap_checked
                              << " points: " << gaps.text();
    EXPECT_EQ(overlaps.count, 0u) << "overlaps, of " << overlap_checked
                                  << " points: " << overlaps.text();
  }
}

// Polygons cut at the antimeridian and Antarctica reaching the pole, in web
// mercator: points that OGR finds inside Fiji or Russia on either side of
// +-180 (and farther than 1.5 px of the zoom from their borders other than
// the cut) are covered by that country in the tiles at both edges of the
// world, at zoom 4 (the whole world) and 6 (a --where build of the three);
// points inside Antarctica between 85.04 and 80 degrees south are covered by
// it, down to the bottom row of tiles, which web mercator ends at 85.05 S.
TEST(AreasMvt, AntimeridianAndPoleFill) {
  if (!have_samples({"world.gpkg"})) GTEST_SKIP() << "samples/data/world.gpkg missing";
  const fs::path w = world();
  ASSERT_FALSE(w.empty()) << "building the world package failed (above)";
  const fs::path am = built("antimeridian", "world.gpkg",
                            std::string(kWhereAntimeridian) + " --min-zoom 6 --max-zoom 6");
  ASSERT_FALSE(am.empty()) << "building the Fiji, Russia and Antarctica package failed (above)";
  const auto source = read_source(samples() / "world.gpkg", "name_long");
  auto find = [&](const std::string& name) -> const SourceFeature* {
    for (const SourceFeature& s : source)
      if (s.key == name) return &s;
    return nullptr;
  };
  for (const char* name : {"Fiji", "Russian Federation", "Antarctica"})
    ASSERT_NE(find(name), nullptr) << name << " is not in world.gpkg";

  struct Zoom {
    fs::path dir;
    int z;
  };
  for (const Zoom& zoom : {Zoom{w, 4}, Zoom{am, 6}}) {
    const int z = zoom.z;
    SCOPED_TRACE("zoom " + std::to_string(z));
    const Tiles tiles = read_zoom(zoom.dir / "mvt", z);
    ASSERT_FALSE(tiles.empty());
    const double margin = 1.5 * px_m(z);
    Problems p;
    // Both sides of the antimeridian.
    struct Area {
      const char* name;
      double lat0, lat1, step;
      int min_west, min_east;  // points each side must have
    };
    for (const Area& a : {Area{"Fiji", -18.6, -15.9, 0.01, z >= 6 ? 5 : 0, 5},
                          Area{"Russian Federation", 64, 72, 0.05, 5, 5}}) {
      const SourceFeature& s = *find(a.name);
      int west = 0, east = 0;
      for (double lat = a.lat0; lat <= a.lat1; lat += a.step)
        for (double lon = -180 + a.step / 2; lon < 180; lon += a.step) {
          if (std::abs(lon) < 177) {
            lon = 177;  // skip to the eastern side
            continue;
          }
          const P pt{merc_x(lon), merc_y(lat)};
          if (!s.merc.contains(pt) || s.merc.near(pt, margin)) continue;
          (lon < 0 ? west : east)++;
          const auto got = covering(tiles, pt, z);
          if (std::none_of(got.begin(), got.end(),
                           [&](const Decoded* d) { return d->key("name_long") == a.name; }))
            p.add(where(pt, z) + ": inside " + a.name + " in the source, tiles give " +
                  names(got, "name_long"));
        }
      EXPECT_GE(west, a.min_west) << a.name << ": too few points west of 180 to check";
      EXPECT_GE(east, a.min_east) << a.name << ": too few points east of 180 to check";
    }
    // Antarctica towards the pole.
    const SourceFeature& ant = *find("Antarctica");
    int bottom = 0, checked = 0;
    for (double lat = -85.04; lat <= -80; lat += 0.25)
      for (double lon = -178.75; lon < 180; lon += 2.5) {
        const P pt{merc_x(lon), merc_y(lat)};
        if (!ant.merc.contains(pt) || ant.merc.near(pt, margin)) continue;
        ++checked;
        bottom += tile_of(pt, z).y == (1 << z) - 1;
        const auto got = covering(tiles, pt, z);
        if (std::none_of(got.begin(), got.end(),
                         [](const Decoded* d) { return d->key("name_long") == "Antarctica"; }))
          p.add(where(pt, z) + ": inside Antarctica in the source, tiles give " +
                names(got, "name_long"));
      }
    EXPECT_GT(checked, 100);
    EXPECT_GT(bottom, 50) << "few Antarctic points in the bottom row of tiles";
    EXPECT_EQ(p.count, 0u) << p.text();
  }
}

// A choropleth of population density (pop / area_km2) in 5 quantile classes
// of YlOrRd: `info --json` gives the classes, whose breaks are R's quantile
// type 7 of the densities (computed here from OGR's reading of the features
// with both fields, area > 0) and whose colours are ColorBrewer's YlOrRd-5;
// every MVT feature's "value" is its density; the style's fill colour is a
// step expression with the same breaks and colours.
TEST(AreasChoropleth, ClassesAndStyleMatchTheBreaks) {
  if (!have_samples({"world.gpkg"})) GTEST_SKIP() << "samples/data/world.gpkg missing";
  const fs::path d =
      built("choropleth", "world.gpkg",
            "--max-zoom 2 --choropleth pop/area_km2 --classes 5 --method quantile --colors YlOrRd");
  ASSERT_FALSE(d.empty()) << "building the choropleth package failed (above)";
  const auto source = read_source(samples() / "world.gpkg", "name_long");
  std::map<std::string, double> density;
  std::vector<double> v;
  for (const SourceFeature& s : source)
    if (s.num.count("pop") && s.num.count("area_km2") && s.num.at("area_km2") > 0) {
      density[s.key] = s.num.at("pop") / s.num.at("area_km2");
      v.push_back(density[s.key]);
    }
  ASSERT_GT(v.size(), 100u);
  std::sort(v.begin(), v.end());
  auto quantile7 = [&](double prob) {
    const double h = double(v.size() - 1) * prob;
    const size_t lo = size_t(std::floor(h));
    return lo + 1 < v.size() ? v[lo] + (h - double(lo)) * (v[lo + 1] - v[lo]) : v[lo];
  };
  std::vector<double> breaks;  // 0 %, 20 %, ..., 100 %
  for (int k = 0; k <= 5; ++k)
    breaks.push_back(quantile7(k / 5.0));
  const std::vector<std::string> colors = {"#ffffb2", "#fecc5c", "#fd8d3c", "#f03b20", "#bd0026"};
  auto same = [](double a, double b, double rel) {
    return std::abs(a - b) <= rel * std::max(std::abs(a), std::abs(b));
  };
  auto lower = [](std::string s) {
    for (char& c : s)
      c = char(std::tolower(static_cast<unsigned char>(c)));
    return s;
  };

  TempDir scratch;
  const RunResult info =
      run(vectorize() + " info " + (d / "choropleth.mbtiles").string() + " --json", scratch.path());
  ASSERT_EQ(info.exit_code, 0) << info.err;
  const JsonValue j = JsonValue::parse(info.out);
  ASSERT_NE(j.find("kind"), nullptr) << info.out;
  EXPECT_EQ(j.find("kind")->string(), "areas");
  const JsonValue* areas = j.find("areas");
  ASSERT_NE(areas, nullptr) << info.out;
  const JsonValue* choropleth = areas->find("choropleth");
  ASSERT_NE(choropleth, nullptr) << info.out;
  ASSERT_NE(choropleth->find("field"), nullptr) << choropleth->text();
  EXPECT_EQ(choropleth->find("field")->string().rfind("pop", 0), 0u) << choropleth->text();
  ASSERT_NE(choropleth->find("method"), nullptr) << choropleth->text();
  EXPECT_EQ(choropleth->find("method")->string(), "quantile");
  ASSERT_NE(areas->find("classes"), nullptr) << info.out;
  const auto& classes = areas->find("classes")->array();
  ASSERT_EQ(classes.size(), 5u) << areas->text();
  for (size_t i = 0; i < 5; ++i) {
    const double lo = number(classes[i], "min"), hi = number(classes[i], "max");
    EXPECT_TRUE(same(lo, breaks[i], 1e-9))
        << "class " << i << " min " << g17(lo) << ", quantile type 7 " << g17(breaks[i]);
    EXPECT_TRUE(same(hi, breaks[i + 1], 1e-9))
        << "class " << i << " max " << g17(hi) << ", quantile type 7 " << g17(breaks[i + 1]);
    EXPECT_LE(lo, hi);
    const JsonValue* color = classes[i].find("color");
    EXPECT_TRUE(color && color->is_string() && lower(color->string()) == colors[i])
        << "class " << i << ": " << classes[i].text() << ", YlOrRd-5 has " << colors[i];
  }
  EXPECT_TRUE(same(number(classes.front(), "min"), v.front(), 1e-9))
      << "the first class starts at " << g17(number(classes.front(), "min"))
      << ", not at the smallest density, " << g17(v.front());
  EXPECT_TRUE(same(number(classes.back(), "max"), v.back(), 1e-9))
      << "the last class ends at " << g17(number(classes.back(), "max"))
      << ", not at the largest density, " << g17(v.back());

  // Each feature's value, in every tile of the finest zoom.
  size_t valued = 0;
  Problems p;
  for (const auto& [k, features] : read_zoom(d / "mvt", 2))
    for (const Decoded& f : features) {
      const auto it = density.find(f.key("name_long"));
      if (it == density.end()) continue;
      if (!f.fields.count("value")) {
        p.add(k.str() + " " + it->first + ": no value tag");
        continue;
      }
      const double got = std::stod(f.fields.at("value"));
      ++valued;
      if (!same(got, it->second, 1e-6))
        p.add(k.str() + " " + it->first + ": value " + f.fields.at("value") + ", pop/area_km2 " +
              g17(it->second));
    }
  EXPECT_GT(valued, density.size());
  EXPECT_EQ(p.count, 0u) << p.text();

  // The style: a fill layer coloured by step over "value".
  ASSERT_TRUE(fs::exists(d / "style.json"));
  const JsonValue style = JsonValue::parse(read_file(d / "style.json"));
  const JsonValue* fill = nullptr;
  for (const JsonValue& l : style.find("layers")->array())
    if (l.find("type") && l.find("type")->string() == "fill") fill = &l;
  ASSERT_NE(fill, nullptr) << read_file(d / "style.json");
  ASSERT_NE(fill->find("paint"), nullptr) << fill->text();
  const JsonValue* color = fill->find("paint")->find("fill-color");
  ASSERT_NE(color, nullptr) << fill->text();
  ASSERT_TRUE(color->is_array()) << color->text();
  const auto& e = color->array();
  ASSERT_EQ(e.size(), 2u + 2 * 5 - 1) << color->text();
  EXPECT_EQ(e[0].text(), "\"step\"");
  EXPECT_EQ(e[1].text(), R"(["get","value"])");
  EXPECT_EQ(lower(e[2].string()), colors[0]) << color->text();
  for (size_t i = 1; i < 5; ++i) {
    EXPECT_TRUE(same(e[1 + 2 * i].number(), breaks[i], 1e-9))
        << "break " << i << ": " << e[1 + 2 * i].text() << ", quantile type 7 " << g17(breaks[i]);
    EXPECT_EQ(lower(e[2 + 2 * i].string()), colors[i]) << color->text();
  }
}

// Refusals: a source without a polygon (exit 1, bad input, naming the file),
// a choropleth field the source lacks and an unknown classification method
// (exit 2, naming them); nothing is left under the output's name.
TEST(AreasCli, BadInputIsRefusedClearly) {
  if (!have_samples({"world.gpkg"})) GTEST_SKIP() << "samples/data/world.gpkg missing";
  TempDir dir;
  const fs::path lines = dir / "only_lines.geojson";
  std::ofstream(lines)
      << R"({"type":"FeatureCollection","features":[)"
      << R"({"type":"Feature","properties":{"name":"a"},"geometry":{"type":"LineString","coordinates":[[7.0,46.9],[7.4,46.95],[7.9,47.3]]}},)"
      << R"({"type":"Feature","properties":{"name":"b"},"geometry":{"type":"LineString","coordinates":[[6.1,46.2],[6.6,46.5]]}}]})";
  const std::string world_src = (samples() / "world.gpkg").string();
  struct Case {
    std::string what, args;
    int code;
    std::string named;
  };
  for (const Case& c :
       {Case{"lines only", lines.string(), 1, "only_lines.geojson"},
        Case{"no such field",
             world_src + " --choropleth nosuchfield --classes 5 --method quantile --colors YlOrRd",
             2, "nosuchfield"},
        Case{"bogus method",
             world_src + " --choropleth pop --classes 5 --method bogus --colors YlOrRd", 2,
             "bogus"}}) {
    SCOPED_TRACE(c.what);
    const fs::path out = dir / "out.mbtiles";
    const RunResult r =
        run(vectorize() + " areas -q " + c.args + " -o " + out.string(), dir.path());
    EXPECT_EQ(r.exit_code, c.code) << r.err;
    EXPECT_NE(r.err.find(c.named), std::string::npos) << "stderr does not name " << c.named << ":\n"
                                                      << r.err;
    EXPECT_FALSE(fs::exists(out)) << "a package was left under the output name";
    EXPECT_FALSE(fs::exists(dir / "out.mbtiles.tmp")) << "out.mbtiles.tmp was left";
    EXPECT_FALSE(fs::exists(dir / "out.mbtiles.staging")) << "out.mbtiles.staging was left";
  }
}

// `extract` of North Carolina's finest zoom writes valid polygons in the
// tiling CRS (web mercator here, as `extract` of every kind) with feature_id,
// tile and properties; a county's pieces, each cut to its own
// tile, add up to the source county's area within 1 % (both in EPSG:5070).
TEST(AreasExtract, PolygonsComeBackInTheTilingCrs) {
  if (!have_samples({"nc.gpkg"})) GTEST_SKIP() << "samples/data/nc.gpkg missing";
  const fs::path n = nc();
  ASSERT_FALSE(n.empty()) << "building the North Carolina package failed (above)";
  TempDir dir;
  const fs::path out = dir / "z9.gpkg";
  const RunResult r = run(
      vectorize() + " extract -q " + (n / "nc.mbtiles").string() + " --zoom 9 -o " + out.string(),
      dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  gdal_setup();
  OGRSpatialReferenceH albers = srs_from("EPSG:5070");

  // The source counties' areas.
  std::map<std::string, double> want;
  {
    GDALDatasetH ds =
        GDALOpenEx((samples() / "nc.gpkg").c_str(), GDAL_OF_VECTOR, nullptr, nullptr, nullptr);
    ASSERT_NE(ds, nullptr);
    OGRLayerH layer = GDALDatasetGetLayer(ds, 0);
    OGRSpatialReferenceH from = OSRClone(OGR_L_GetSpatialRef(layer));
    OSRSetAxisMappingStrategy(from, OAMS_TRADITIONAL_GIS_ORDER);
    OGRCoordinateTransformationH ct = OCTNewCoordinateTransformation(from, albers);
    while (OGRFeatureH f = OGR_L_GetNextFeature(layer)) {
      OGRGeometryH g = OGR_G_Clone(OGR_F_GetGeometryRef(f));
      EXPECT_EQ(OGR_G_Transform(g, ct), OGRERR_NONE);
      want[OGR_F_GetFieldAsString(f, OGR_F_GetFieldIndex(f, "NAME"))] = OGR_G_Area(g);
      OGR_G_DestroyGeometry(g);
      OGR_F_Destroy(f);
    }
    OCTDestroyCoordinateTransformation(ct);
    OSRRelease(from);
    GDALClose(ds);
  }
  ASSERT_EQ(want.size(), 100u);

  GDALDatasetH ds = GDALOpenEx(out.c_str(), GDAL_OF_VECTOR, nullptr, nullptr, nullptr);
  ASSERT_NE(ds, nullptr) << "OGR cannot open the extract";
  ASSERT_GE(GDALDatasetGetLayerCount(ds), 1);
  OGRLayerH layer = GDALDatasetGetLayer(ds, 0);
  OGRSpatialReferenceH srs = OGR_L_GetSpatialRef(layer);
  ASSERT_NE(srs, nullptr) << "the extract has no CRS";
  EXPECT_NE(std::string(OSRGetName(srs) ? OSRGetName(srs) : "").find("Pseudo-Mercator"),
            std::string::npos)
      << "the extract is not in the tiling CRS but in "
      << (OSRGetName(srs) ? OSRGetName(srs) : "?");
  // The rest is checked in lon/lat.
  OGRSpatialReferenceH lonlat = srs_from("EPSG:4326"), own = OSRClone(srs);
  OSRSetAxisMappingStrategy(own, OAMS_TRADITIONAL_GIS_ORDER);
  OGRCoordinateTransformationH ct = OCTNewCoordinateTransformation(lonlat, albers);
  OGRCoordinateTransformationH to_lonlat = OCTNewCoordinateTransformation(own, lonlat);
  OGRFeatureDefnH defn = OGR_L_GetLayerDefn(layer);
  for (const char* f : {"feature_id", "tile", "properties"})
    EXPECT_GE(OGR_FD_GetFieldIndex(defn, f), 0) << "no field " << f;
  // county -> tile -> its pieces there (lon/lat)
  std::map<std::string, std::map<std::string, std::vector<OGRGeometryH>>> pieces;
  Problems p;
  size_t count = 0;
  OGR_L_ResetReading(layer);
  while (OGRFeatureH f = OGR_L_GetNextFeature(layer)) {
    ++count;
    const std::string tile = OGR_F_GetFieldAsString(f, OGR_F_GetFieldIndex(f, "tile"));
    const std::string props = OGR_F_GetFieldAsString(f, OGR_F_GetFieldIndex(f, "properties"));
    const std::string id = "tile " + tile + " feature " +
                           OGR_F_GetFieldAsString(f, OGR_F_GetFieldIndex(f, "feature_id"));
    std::string name;
    try {
      const JsonValue j = JsonValue::parse(props);
      if (j.find("NAME")) name = j.find("NAME")->string();
    } catch (const std::exception&) {
      p.add(id + ": properties are not JSON: " + props);
    }
    OGRGeometryH g = OGR_F_GetGeometryRef(f);
    if (!g) {
      p.add(id + ": no geometry");
    } else {
      const OGRwkbGeometryType t = wkbFlatten(OGR_G_GetGeometryType(g));
      OGRGeometryH ll = OGR_G_Clone(g);
      const bool moved = OGR_G_Transform(ll, to_lonlat) == OGRERR_NONE;
      OGREnvelope env;
      OGR_G_GetEnvelope(ll, &env);
      if (t != wkbPolygon && t != wkbMultiPolygon)
        p.add(id + ": geometry type " + OGRGeometryTypeToName(t));
      else if (!OGR_G_IsValid(g))
        p.add(id + " (" + name + "): invalid (GEOS): " + wkt_start(g));
      else if (!moved || env.MinX < -85 || env.MaxX > -75 || env.MinY < 33 || env.MaxY > 37.5)
        p.add(id + " (" + name + "): not over North Carolina: " + wkt_start(ll, 120));
      else if (name.empty())
        p.add(id + ": no NAME in properties " + props);
      else
        pieces[name][tile].push_back(OGR_G_Clone(ll));
      OGR_G_DestroyGeometry(ll);
    }
    OGR_F_Destroy(f);
  }
  GDALClose(ds);
  EXPECT_GT(count, 100u);
  EXPECT_EQ(p.count, 0u) << p.text();

  Problems areas;
  for (const auto& [name, want_area] : want) {
    const auto it = pieces.find(name);
    if (it == pieces.end()) {
      areas.add(name + ": not in the extract");
      continue;
    }
    double got = 0;
    for (const auto& [tile, parts] : it->second) {
      int z = 0, x = 0, y = 0;
      if (std::sscanf(tile.c_str(), "%d/%d/%d", &z, &x, &y) != 3) {
        areas.add(name + ": tile '" + tile + "' is not z/x/y");
        continue;
      }
      const double w = double(x) / (1 << z) * 360 - 180, e = double(x + 1) / (1 << z) * 360 - 180;
      const double nth = lat_of(kHalf - y * tile_m(z)), sth = lat_of(kHalf - (y + 1) * tile_m(z));
      OGRGeometryH ring = OGR_G_CreateGeometry(wkbLinearRing);
      OGR_G_AddPoint_2D(ring, w, sth);
      OGR_G_AddPoint_2D(ring, w, nth);
      OGR_G_AddPoint_2D(ring, e, nth);
      OGR_G_AddPoint_2D(ring, e, sth);
      OGR_G_AddPoint_2D(ring, w, sth);
      OGRGeometryH box = OGR_G_CreateGeometry(wkbPolygon);
      OGR_G_AddGeometryDirectly(box, ring);
      OGRGeometryH all = OGR_G_Clone(parts.front());
      for (size_t i = 1; i < parts.size(); ++i) {
        OGRGeometryH u = OGR_G_Union(all, parts[i]);
        OGR_G_DestroyGeometry(all);
        all = u;
      }
      OGRGeometryH in = all ? OGR_G_Intersection(all, box) : nullptr;
      if (!in) {
        areas.add(name + " in " + tile + ": GEOS cannot cut it to its tile");
      } else {
        if (OGR_G_Transform(in, ct) == OGRERR_NONE) got += OGR_G_Area(in);
        OGR_G_DestroyGeometry(in);
      }
      if (all) OGR_G_DestroyGeometry(all);
      OGR_G_DestroyGeometry(box);
    }
    if (std::abs(got - want_area) > 0.01 * want_area)
      areas.add(name + ": " + std::to_string(got / 1e6) + " km2 in the extract, " +
                std::to_string(want_area / 1e6) + " km2 in the source");
  }
  for (auto& [name, tiles] : pieces)
    for (auto& [tile, parts] : tiles)
      for (OGRGeometryH g : parts)
        OGR_G_DestroyGeometry(g);
  OCTDestroyCoordinateTransformation(ct);
  OCTDestroyCoordinateTransformation(to_lonlat);
  OSRRelease(own);
  OSRRelease(lonlat);
  OSRRelease(albers);
  EXPECT_EQ(areas.count, 0u) << areas.text();
}

namespace {

// The same input and options give the same package for any thread count:
// world.gpkg as a choropleth (the classes, GEOS's per-thread contexts, the
// pieces sorted by tile) at -j 1 and -j 2, each written as a.mbtiles.
TEST(AreasCli, OneAndTwoThreadsWriteTheSamePackage) {
  if (!have_samples({"world.gpkg"})) GTEST_SKIP() << "samples/data/world.gpkg missing";
  TempDir dir;
  for (const char* j : {"1", "2"}) {
    fs::create_directories(dir / j);
    const RunResult r = run(vectorize() + " areas -q " + (samples() / "world.gpkg").string() +
                                " --max-zoom 4 --choropleth pop/area_km2 --method jenks -j " + j +
                                " -o " + (dir / j / "a.mbtiles").string(),
                            dir.path());
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  expect_same_package((dir / "2" / "a.mbtiles").string(), (dir / "1" / "a.mbtiles").string());
}

}  // namespace
