// globe-tiler export (docs/web.md) as users run it, checked with references
// that share no code with it: the PMTiles and raster-DEM readers written from
// the specifications (spec_readers/), GDAL's PNG driver, the sqlite3 program
// and an analytic surface. (In a real client: web_maplibre_test.cpp.)
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <map>
#include <set>
#include <sstream>

#include <gdal.h>

#include "raster_fixtures.hpp"
#include "spec_readers/pmtiles_reader.hpp"
#include "spec_readers/raster_dem.hpp"
#include "test_support.hpp"
#include "tileformat/json.hpp"
#include "tileformat/package.hpp"
#include "web_fixtures.hpp"
#include "web_surfaces.hpp"

namespace {

using namespace globe_test;
namespace pmr = spec_readers::pmtiles;
namespace dem = spec_readers::raster_dem;

struct PixelErrors {
  size_t pixels = 0, beyond = 0;
  double worst = 0;  // metres beyond the bound (<= 0: all within)
  std::string where;
};

// Every pixel of every tile of a raster-DEM PMTiles export whose centre lies
// well inside the surface's area, against the surface at that centre. The
// bound: the package's height step / 2, Terrarium's 1/512 m, and bilinear
// interpolation between samples no farther apart than the pixels (and the
// source grid's own): |h_xx| dx^2 / 8 + |h_yy| dy^2 / 8 + |h_xy| dx dy / 4.
// `wanted(z, x, y)`: the tiles to check.
PixelErrors check_surface_export(const std::string& pmtiles, double height_step, const Surface& f,
                                 const std::function<bool(int, uint32_t, uint32_t)>& wanted) {
  const std::string file = read_file(pmtiles);
  PixelErrors e;
  e.worst = -1e300;
  for (const pmr::Entry& entry : pmr::validate_archive(file)) {
    for (uint32_t r = 0; r < entry.run_length; ++r) {
      const pmr::TileCoord t = pmr::tile_id_to_zxy(entry.tile_id + r);
      if (!wanted(t.z, t.x, t.y)) continue;
      int w = 0, h = 0;
      const auto rgb = png_rgb(
          file.substr(pmr::read_header(file).tile_data_offset + entry.offset, entry.length), w, h);
      EXPECT_EQ(w, 256);
      if (rgb.empty()) {
        ADD_FAILURE() << "tile " << int(t.z) << "/" << t.x << "/" << t.y << " is not a PNG";
        continue;
      }
      const double pix = 360.0 / (std::ldexp(1.0, t.z) * w);  // degrees of longitude
      const double d2 = std::max(pix, f.source) * std::max(pix, f.source);
      const double bound = height_step / 2 + 1.0 / 512 + 0.02 +
                           f.amp * (f.kx * f.kx * d2 + f.ky * f.ky * d2) / 8 +
                           f.amp * f.kx * f.ky * d2 / 4 +
                           f.amp * (f.kx * f.kx + f.ky * f.ky) * f.source * f.source / 8;
      const double margin = 2 * std::max(pix, f.source) + 2 * f.source;
      const double lon_margin = f.global() ? 0 : margin;
      for (int py = 0; py < h; ++py)
        for (int px = 0; px < w; ++px) {
          const dem::LonLat c = dem::pixel_center_lon_lat(t.z, t.x, t.y, px, py, w);
          if (c.lon_deg < f.west + lon_margin || c.lon_deg > f.east - lon_margin ||
              c.lat_deg < f.south + margin || c.lat_deg > f.north - margin)
            continue;
          const double got =
              dem::pixel_height(rgb.data(), w, h, 3, px, py, dem::Encoding::Terrarium);
          const double err = std::fabs(got - f.at(c.lon_deg, c.lat_deg)) - bound;
          ++e.pixels;
          if (err > 0) ++e.beyond;
          if (err > e.worst) {
            e.worst = err;
            std::ostringstream where;
            where << int(t.z) << "/" << t.x << "/" << t.y << " pixel " << px << "," << py << ": "
                  << got << " m, surface " << f.at(c.lon_deg, c.lat_deg) << " m, bound " << bound;
            e.where = where.str();
          }
        }
    }
  }
  return e;
}

double height_step(const std::string& pkg, const fs::path& dir) {
  const RunResult r = run(
      "sqlite3 " + pkg + " \"SELECT value FROM metadata WHERE name = 'globe:height_step'\"", dir);
  return std::stod(r.out);
}

// Exports the webmercator and the geodetic package of `f` (in `packages`) to
// Terrarium PMTiles and checks the `wanted` tiles' pixels against `f`.
void expect_surface_exports(const fs::path& packages, const Surface& f,
                            const std::function<bool(int, uint32_t, uint32_t)>& wanted,
                            size_t min_pixels) {
  TempDir dir;
  for (const char* tiling : {"mercator", "geodetic"}) {
    const std::string pkg = (packages / (std::string(tiling) + ".mbtiles")).string();
    const std::string out = (dir / (std::string(tiling) + ".pmtiles")).string();
    const RunResult r =
        run(tiler() + " export " + pkg + " --format terrarium -o " + out, dir.path());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const PixelErrors e = check_surface_export(out, height_step(pkg, dir.path()), f, wanted);
    EXPECT_GT(e.pixels, min_pixels) << tiling;
    EXPECT_EQ(e.beyond, 0u) << tiling << ": " << e.beyond << " of " << e.pixels
                            << " pixels beyond the bound; worst " << e.where;
  }
}

}  // namespace

// Both tilings: a webmercator package keeps its tiles, a geodetic one is
// resampled to web mercator; every pixel is the surface at its centre within
// the bound of bilinear interpolation between samples.
TEST(ExportDem, TerrariumPixelsAreTheSurfaceAtTheirCentres) {
  expect_surface_exports(
      surface_dem(), kRegional, [](int, uint32_t, uint32_t) { return true; }, 100000);
}

// A global grid, in both tilings: the tiles of zooms 0..3 whole and, at every
// finer zoom, the columns on either side of 180 degrees, every pixel up to
// 85.05 degrees of latitude within the same bound (a pixel next to 180 E
// interpolates up to the blocks' samples on 180 itself).
TEST(ExportDem, GlobalGridsWrapAtTheAntimeridian) {
  expect_surface_exports(
      surface_packages(kGlobal, "global"), kGlobal,
      [](int z, uint32_t x, uint32_t) { return z <= 3 || x == 0 || x + 1 == (1u << z); }, 1000000);
}

// Terrain-RGB into a folder and Terrarium into MBTiles hold the same heights
// (within Terrain-RGB's 0.1 m); the folder says its encoding in
// metadata.json; the MBTiles rows count from the south (TMS), as the sqlite3
// program reads them.
TEST(ExportDem, FoldersAndMbtilesHoldTheSameHeights) {
  const fs::path& d = surface_dem();
  TempDir dir;
  const std::string pkg = (d / "mercator.mbtiles").string();
  const std::string folder = (dir / "rgb").string(), mb = (dir / "t.mbtiles").string();
  ASSERT_EQ(run(tiler() + " export -q " + pkg + " --format terrain-rgb -o " + folder, dir.path())
                .exit_code,
            0);
  ASSERT_EQ(
      run(tiler() + " export -q " + pkg + " --format terrarium -o " + mb, dir.path()).exit_code, 0);
  const auto meta = tileformat::JsonValue::parse(read_file(fs::path(folder) / "metadata.json"));
  EXPECT_EQ(meta.find("encoding")->string(), "mapbox");
  EXPECT_EQ(meta.find("tiles")->array()[0].string(), "{z}/{x}/{y}.png");
  size_t tiles = 0;
  for (const auto& f : fs::recursive_directory_iterator(folder)) {
    if (f.path().extension() != ".png") continue;
    const int y = std::stoi(f.path().stem().string());
    const int x = std::stoi(f.path().parent_path().filename().string());
    const int z = std::stoi(f.path().parent_path().parent_path().filename().string());
    const std::string hex = (dir / "tile.png").string();
    const RunResult r = run("sqlite3 " + mb + " \"SELECT writefile('" + hex +
                                "', tile_data) FROM tiles WHERE zoom_level = " + std::to_string(z) +
                                " AND tile_column = " + std::to_string(x) +
                                " AND tile_row = " + std::to_string((1 << z) - 1 - y) + "\"",
                            dir.path());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    int w1 = 0, h1 = 0, w2 = 0, h2 = 0;
    const auto rgb = png_rgb(read_file(f.path()), w1, h1);
    const auto terrarium = png_rgb(read_file(hex), w2, h2);
    ASSERT_EQ(rgb.size(), terrarium.size()) << f.path();
    ASSERT_FALSE(rgb.empty());
    double worst = 0;
    for (int py = 0; py < h1; py += 3)
      for (int px = 0; px < w1; px += 3)
        worst = std::max(worst, std::fabs(dem::pixel_height(rgb.data(), w1, h1, 3, px, py,
                                                            dem::Encoding::TerrainRgb) -
                                          dem::pixel_height(terrarium.data(), w2, h2, 3, px, py,
                                                            dem::Encoding::Terrarium)));
    EXPECT_LE(worst, 0.05 + 1.0 / 512) << f.path();
    ++tiles;
  }
  EXPECT_GT(tiles, 10u);
}

TEST(ExportDem, BadInputIsRefusedAndLeavesNothing) {
  const fs::path& d = surface_dem();
  TempDir dir;
  const std::string pkg = (d / "mercator.mbtiles").string();
  auto refused = [&](const std::string& args, int code, const std::string& says,
                     const std::string& out) {
    const RunResult r = run(tiler() + " export " + args, dir.path());
    EXPECT_EQ(r.exit_code, code) << args << "\n" << r.err;
    EXPECT_NE(r.err.find(says), std::string::npos) << args << "\n" << r.err;
    if (!out.empty()) {
      EXPECT_FALSE(fs::exists(out + ".tmp")) << args;
      EXPECT_FALSE(fs::exists(out + ".tiles.tmp")) << args;
    }
  };
  const std::string out = (dir / "out.pmtiles").string();
  refused(pkg + " -o " + out, 2, "give --format terrarium, terrain-rgb or quantized-mesh", out);
  refused(pkg + " --format png -o " + out, 2,
          "--format: 'png' is not terrarium, terrain-rgb or quantized-mesh", out);
  refused(pkg + " --format terrarium --tile-size 300 -o " + out, 2, "--tile-size: 256 or 512", out);
  refused((dir / "missing.mbtiles").string() + " --format terrarium -o " + out, 1,
          "missing.mbtiles", out);
  EXPECT_FALSE(fs::exists(out));
  // A local tiling cannot become web mercator.
  const double gt[6] = {500000, 30, 0, 5200000, 0, -30};
  write_dem((dir / "utm.tif").string(), 64, 64, gt, "EPSG:32632", GDT_Float32,
            [](int x, int y) { return 100.0 + x + y; });
  const std::string local = (dir / "local.mbtiles").string();
  ASSERT_EQ(
      run(tiler() + " terrain -q --tiling local " + (dir / "utm.tif").string() + " -o " + local,
          dir.path())
          .exit_code,
      0);
  refused(local + " --format terrarium -o " + out, 2, "local tiling cannot become web mercator",
          out);
  // An existing output stays as it was without --force.
  std::ofstream(out) << "keep";
  refused(pkg + " --format terrarium -o " + out, 3, "output exists; pass --force", "");
  EXPECT_EQ(read_file(out), "keep");
  EXPECT_EQ(run(tiler() + " export -q --force " + pkg + " --format terrarium -o " + out, dir.path())
                .exit_code,
            0);
  EXPECT_NO_THROW(pmr::validate_archive(read_file(out)));
}

// A folder output named with a trailing slash is the same folder (issue 55:
// `-o out/` made `out/.tmp` inside the output, did all the work, then found
// `out` existing and exited 3 with an empty folder). Written the first time,
// refused the second before anything is made (no temporary folder), replaced
// with --force; for quantized-mesh, Terrarium and MVT folders alike.
TEST(ExportFolders, ATrailingSlashNamesTheSameFolder) {
  const fs::path& d = surface_dem();
  TempDir dir;
  std::ofstream(dir / "line.geojson")
      << R"({"type":"FeatureCollection","features":[{"type":"Feature","properties":{},)"
      << R"("geometry":{"type":"LineString","coordinates":[[7.0,46.9],[8.2,47.6]]}}]})";
  ASSERT_EQ(run(vectorize() + " lines -q " + (dir / "line.geojson").string() + " --max-zoom 5 -o " +
                    (dir / "line.mbtiles").string(),
                dir.path())
                .exit_code,
            0);
  const std::vector<std::pair<std::string, std::string>> exports = {
      {tiler() + " export -q " + (d / "geodetic.mbtiles").string() + " --format quantized-mesh",
       "qm"},
      {tiler() + " export -q " + (d / "mercator.mbtiles").string() + " --format terrarium", "dem"},
      {vectorize() + " export -q " + (dir / "line.mbtiles").string(), "mvt"}};
  for (const auto& [command, name] : exports) {
    const fs::path out = dir / name;
    const RunResult first = run(command + " -o " + out.string() + "/", dir.path());
    ASSERT_EQ(first.exit_code, 0) << command << "\n" << first.err;
    ASSERT_TRUE(fs::is_directory(out)) << name;
    EXPECT_TRUE(fs::exists(out / "metadata.json")) << name;
    EXPECT_FALSE(fs::exists(out / ".tmp")) << name;
    size_t files = 0;
    for (const auto& e : fs::recursive_directory_iterator(out))
      files += e.is_regular_file() ? 1 : 0;
    EXPECT_GT(files, 2u) << name << ": the tiles are in the folder";
    const RunResult again = run(command + " -o " + out.string() + "/", dir.path());
    EXPECT_EQ(again.exit_code, 3) << name << "\n" << again.err;
    EXPECT_NE(again.err.find("output exists; pass --force"), std::string::npos) << again.err;
    EXPECT_FALSE(fs::exists(dir / (name + ".tmp"))) << name << ": refused before any work";
    EXPECT_EQ(run(command + " --force -o " + out.string() + "//", dir.path()).exit_code, 0) << name;
    EXPECT_TRUE(fs::exists(out / "metadata.json")) << name;
  }
}

// An image package's tiles, exported to PMTiles, are the package's bytes
// (read from the package here, the exporter's input), tile for tile.
TEST(ExportImages, PmtilesHoldThePackagesTilesByteForByte) {
  TempDir dir;
  const double gt[6] = {10, 0.01, 0, 47, 0, -0.01};
  gdal_setup();
  const std::string tif = (dir / "rgb.tif").string();
  GDALDatasetH ds =
      GDALCreate(GDALGetDriverByName("GTiff"), tif.c_str(), 300, 200, 3, GDT_Byte, nullptr);
  GDALSetGeoTransform(ds, const_cast<double*>(gt));
  OGRSpatialReferenceH srs = OSRNewSpatialReference(nullptr);
  OSRSetFromUserInput(srs, "EPSG:4326");
  GDALSetSpatialRef(ds, srs);
  OSRRelease(srs);
  std::vector<uint8_t> band(300 * 200);
  for (int b = 0; b < 3; ++b) {
    for (int i = 0; i < 300 * 200; ++i)
      band[size_t(i)] = static_cast<uint8_t>((i % 300) * (b + 1) + (i / 300) * (3 - b));
    ASSERT_EQ(GDALRasterIO(GDALGetRasterBand(ds, b + 1), GF_Write, 0, 0, 300, 200, band.data(), 300,
                           200, GDT_Byte, 0, 0),
              CE_None);
  }
  GDALClose(ds);
  const std::string pkg = (dir / "img.mbtiles").string(), out = (dir / "img.pmtiles").string();
  ASSERT_EQ(run(tiler() + " imagery -q " + tif + " -o " + pkg, dir.path()).exit_code, 0);
  const RunResult r = run(tiler() + " export " + pkg + " -o " + out, dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string file = read_file(out);
  const auto entries = pmr::validate_archive(file);
  EXPECT_EQ(pmr::read_header(file).tile_type, pmr::TileType::Png);
  tileformat::PackageReader reader(pkg);
  size_t tiles = 0;
  reader.for_each_tile([&](tileformat::TileId id, std::span<const uint8_t> blob) {
    const auto got = pmr::get_tile(file, id.z, id.x, id.y);
    ASSERT_TRUE(got.has_value()) << id.str();
    EXPECT_EQ(*got, std::string(blob.begin(), blob.end())) << id.str();
    ++tiles;
  });
  EXPECT_GT(tiles, 3u);
  uint64_t addressed = 0;
  for (const pmr::Entry& e : entries)
    addressed += e.run_length;
  EXPECT_EQ(addressed, tiles);
}

namespace {

struct OgrLine {
  int64_t id = 0;
  std::string layer, cls;
  bool zero_length = false;
  std::vector<std::pair<double, double>> pts;
  std::map<std::string, std::string> fields;
};

// Every feature of an OGR dataset (GDAL's own readers), with its fields as text.
std::vector<OgrLine> read_ogr(const std::string& path, const std::vector<std::string>& options,
                              const char* id_field) {
  gdal_setup();
  std::vector<const char*> opts;
  for (const std::string& o : options)
    opts.push_back(o.c_str());
  opts.push_back(nullptr);
  GDALDatasetH ds = GDALOpenEx(path.c_str(), GDAL_OF_VECTOR, nullptr, opts.data(), nullptr);
  std::vector<OgrLine> out;
  if (!ds) return out;
  for (int l = 0; l < GDALDatasetGetLayerCount(ds); ++l) {
    OGRLayerH layer = GDALDatasetGetLayer(ds, l);
    OGR_L_ResetReading(layer);
    while (OGRFeatureH f = OGR_L_GetNextFeature(layer)) {
      OgrLine line;
      line.layer = OGR_L_GetName(layer);
      OGRFeatureDefnH defn = OGR_F_GetDefnRef(f);
      for (int i = 0; i < OGR_FD_GetFieldCount(defn); ++i)
        if (OGR_F_IsFieldSetAndNotNull(f, i))
          line.fields[OGR_Fld_GetNameRef(OGR_FD_GetFieldDefn(defn, i))] =
              OGR_F_GetFieldAsString(f, i);
      line.id = std::stoll(line.fields[id_field]);
      line.cls = line.fields["class"];
      line.zero_length = line.fields.count("zero_length") && line.fields["zero_length"] != "0";
      if (OGRGeometryH g = OGR_F_GetGeometryRef(f)) {
        const int n = OGR_G_GetPointCount(g);
        for (int i = 0; i < n; ++i)
          line.pts.emplace_back(OGR_G_GetX(g, i), OGR_G_GetY(g, i));
      }
      out.push_back(std::move(line));
      OGR_F_Destroy(f);
    }
  }
  GDALClose(ds);
  return out;
}

double distance_to_line(std::pair<double, double> p,
                        const std::vector<std::pair<double, double>>& l) {
  double best = 1e300;
  for (size_t i = 0; i < l.size(); ++i) {
    const auto a = l[i], b = i + 1 < l.size() ? l[i + 1] : l[i];
    const double dx = b.first - a.first, dy = b.second - a.second, len2 = dx * dx + dy * dy;
    const double t =
        len2 > 0
            ? std::clamp(((p.first - a.first) * dx + (p.second - a.second) * dy) / len2, 0.0, 1.0)
            : 0.0;
    best = std::min(best, std::hypot(p.first - a.first - t * dx, p.second - a.second - t * dy));
  }
  return best;
}

}  // namespace

// Lines in Europe (one 0.8 m long: a single position at zoom 8, which MVT
// cannot hold as a line) as a line package, exported to a folder of MVT: GDAL's MVT driver reads
// every tile of the finest zoom, and each line lies within 1 px (of its zoom) of what
// `globe-vectorize extract` writes for that tile, same id, class and
// attributes; the zero-length line is a point tagged zero_length; the style
// draws each class with its colour.
TEST(ExportMvt, GdalReadsTheLinesExtractWrites) {
  TempDir dir;
  std::ofstream(dir / "lines.geojson")
      << R"({"type":"FeatureCollection","features":[)"
      << R"({"type":"Feature","properties":{"kind":"river","name":"Aare","rank":3},"geometry":{"type":"LineString","coordinates":[[7.0,46.9],[7.4,46.95],[7.9,47.3],[8.2,47.6]]}},)"
      << R"({"type":"Feature","properties":{"kind":"road","name":"A1"},"geometry":{"type":"LineString","coordinates":[[6.1,46.2],[6.6,46.5],[7.4,46.9],[8.5,47.4],[9.4,47.4]]}},)"
      << R"({"type":"Feature","properties":{"kind":"road","name":"spot"},"geometry":{"type":"LineString","coordinates":[[8.0,46.5],[8.00001,46.5]]}}]})";
  const std::string pkg = (dir / "lines.mbtiles").string(), out = (dir / "mvt").string();
  ASSERT_EQ(
      run(vectorize() + " lines -q " + (dir / "lines.geojson").string() +
              " --class-field kind --max-zoom 8 --style 'road:color=#d7301f,width=3px' -o " + pkg,
          dir.path())
          .exit_code,
      0);
  const RunResult r = run(vectorize() + " export " + pkg + " -o " + out + " --style-json " +
                              (dir / "style.json").string(),
                          dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("(1 zero-length lines as points)"), std::string::npos) << r.err;
  const std::string z8 = (dir / "z8.gpkg").string();
  ASSERT_EQ(run(vectorize() + " extract -q " + pkg + " --zoom 8 -o " + z8, dir.path()).exit_code,
            0);
  const auto extracted = read_ogr(z8, {}, "feature_id");
  ASSERT_FALSE(extracted.empty());
  const double tile_m = 2 * 20037508.342789244 / 256, px = tile_m / 256;
  size_t checked = 0, zero = 0;
  std::map<std::string, std::vector<OgrLine>> tiles;  // "x/y" -> MVT features
  for (const OgrLine& e : extracted) {
    const std::string t = e.fields.at("tile");  // "8/x/y"
    const std::string xy = t.substr(t.find('/') + 1);
    if (!tiles.count(xy)) {
      const int x = std::stoi(xy.substr(0, xy.find('/'))),
                y = std::stoi(xy.substr(xy.find('/') + 1));
      tiles[xy] = read_ogr(out + "/8/" + xy + ".pbf",
                           {"X=" + std::to_string(x), "Y=" + std::to_string(y), "Z=8", "CLIP=NO"},
                           "mvt_id");
      ASSERT_FALSE(tiles[xy].empty()) << "tile 8/" << xy << " missing or unreadable";
    }
    const OgrLine* m = nullptr;
    double worst = 1e300;
    for (const OgrLine& c : tiles[xy]) {
      if (c.id != e.id) continue;
      double w = 0;
      for (const auto& p : e.pts)
        w = std::max(w, distance_to_line(p, c.pts));
      if (w < worst) worst = w, m = &c;
    }
    ASSERT_NE(m, nullptr) << "feature " << e.id << " missing from tile 8/" << xy;
    EXPECT_LE(worst, px) << "feature " << e.id << " in tile 8/" << xy;
    EXPECT_EQ(m->cls, e.cls);
    const auto props = tileformat::JsonValue::parse(e.fields.at("properties"));
    for (const auto& [k, v] : props.members())
      if (k != "kind") {
        ASSERT_TRUE(m->fields.count(k)) << k;
        if (v.is_string()) {
          EXPECT_EQ(m->fields.at(k), v.string());
        } else if (v.is_number()) {
          EXPECT_DOUBLE_EQ(std::stod(m->fields.at(k)), v.number());
        }
      }
    zero += m->zero_length;
    ++checked;
  }
  EXPECT_GE(checked, 3u);
  EXPECT_GE(zero, 1u) << "the zero-length line is not a point tagged zero_length";
  const auto style = tileformat::JsonValue::parse(read_file(dir / "style.json"));
  EXPECT_EQ(style.find("version")->number(), 8);
  bool road = false;
  for (const auto& l : style.find("layers")->array())
    if (l.find("filter")->text() == R"(["==",["get","class"],"road"])")
      road = l.find("paint")->find("line-color")->string() == "#d7301f";
  EXPECT_TRUE(road) << read_file(dir / "style.json");
}

// Places (a CSV of 60 across Europe, two fields) as a point package, exported
// to a folder of MVT: GDAL's MVT driver reads the finest zoom's tiles, where
// every place is its own point (--merge-px 0) within 1 px of its CSV position
// with its count and fields; at zoom 0 the counts and sums add up to the CSV's.
TEST(ExportMvt, PointsKeepTheirPositionsCountsAndFields) {
  TempDir dir;
  struct Row {
    double lon, lat, a, b;
  };
  std::vector<Row> rows;
  std::ofstream csv(dir / "places.csv");
  csv << "lon,lat,a,b\n";
  for (int k = 0; k < 60; ++k) {
    const Row r{-9 + 0.37 * k, 38 + std::fmod(k * 0.618, 1.0) * 16, double(k % 7 + 1),
                double(k * 3 % 11)};
    rows.push_back(r);
    csv << r.lon << "," << r.lat << "," << r.a << "," << r.b << "\n";
  }
  csv.close();
  const std::string pkg = (dir / "places.mbtiles").string(), out = (dir / "mvt").string();
  ASSERT_TRUE(run_all({vectorize() + " points -q " + (dir / "places.csv").string() +
                           " --xy lon,lat --fields a,b --merge-px 0 --max-zoom 9 -o " + pkg,
                       vectorize() + " export -q " + pkg + " -o " + out + " --style-json " +
                           (dir / "style.json").string()},
                      dir.path()));
  const double half = 20037508.342789244, px9 = 2 * half / 512 / 256;
  size_t found = 0;
  for (const auto& e : fs::recursive_directory_iterator(fs::path(out) / "9")) {
    if (e.path().extension() != ".pbf") continue;
    const int x = std::stoi(e.path().parent_path().filename().string()),
              y = std::stoi(e.path().stem().string());
    for (const OgrLine& f :
         read_ogr(e.path().string(), {"X=" + std::to_string(x), "Y=" + std::to_string(y), "Z=9"},
                  "mvt_id")) {
      ASSERT_EQ(f.layer, "points");
      ASSERT_EQ(f.pts.size(), 1u);
      EXPECT_EQ(f.fields.at("count"), "1");
      // The CSV place it is: the nearest, within 1 px of zoom 9.
      double best = 1e300;
      const Row* match = nullptr;
      for (const Row& r : rows) {
        const double mx = r.lon / 180 * half,
                     my = std::log(std::tan((90 + r.lat) * kPi / 360)) / kPi * half;
        const double d = std::hypot(mx - f.pts[0].first, my - f.pts[0].second);
        if (d < best) best = d, match = &r;
      }
      ASSERT_LE(best, px9) << "point " << f.id << " in tile 9/" << x << "/" << y;
      EXPECT_EQ(std::stod(f.fields.at("a")), match->a);
      EXPECT_EQ(std::stod(f.fields.at("b")), match->b);
      ++found;
    }
  }
  EXPECT_EQ(found, rows.size());
  double count = 0, a = 0, b = 0;
  for (const OgrLine& f : read_ogr(out + "/0/0/0.pbf", {"X=0", "Y=0", "Z=0"}, "mvt_id")) {
    count += std::stod(f.fields.at("count"));
    a += std::stod(f.fields.at("a"));
    b += std::stod(f.fields.at("b"));
  }
  double ra = 0, rb = 0;
  for (const Row& r : rows)
    ra += r.a, rb += r.b;
  EXPECT_EQ(count, double(rows.size()));
  EXPECT_DOUBLE_EQ(a, ra);
  EXPECT_DOUBLE_EQ(b, rb);
  const auto style = tileformat::JsonValue::parse(read_file(dir / "style.json"));
  EXPECT_EQ(style.find("layers")->array().at(0).find("type")->string(), "circle");
  const auto meta = tileformat::JsonValue::parse(read_file(fs::path(out) / "metadata.json"));
  EXPECT_EQ(meta.find("vector_layers")->array().at(0).find("fields")->find("a")->string(),
            "Number");
}

namespace {

struct LabelRow {
  int64_t feature = 0;
  double lon = 0, lat = 0, priority = 0;
  std::string text;
};

// The labels table of a package, read with the sqlite3 program, by feature.
std::map<int64_t, LabelRow> label_rows(const std::string& pkg, const fs::path& dir) {
  const RunResult r = run("sqlite3 " + pkg +
                              " \"SELECT feature || char(9) || printf('%.17g', lon) || char(9) "
                              "|| printf('%.17g', lat) || char(9) || printf('%.17g', priority) "
                              "|| char(9) || text FROM labels\"",
                          dir);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  std::map<int64_t, LabelRow> out;
  std::istringstream in(r.out);
  for (std::string line; std::getline(in, line);) {
    std::istringstream cols(line);
    LabelRow l;
    std::string f;
    std::getline(cols, f, '\t');
    l.feature = std::stoll(f);
    std::getline(cols, f, '\t');
    l.lon = std::stod(f);
    std::getline(cols, f, '\t');
    l.lat = std::stod(f);
    std::getline(cols, f, '\t');
    l.priority = std::stod(f);
    std::getline(cols, l.text);
    out[l.feature] = l;
  }
  return out;
}

// The features of every tile of zoom `z` of an MVT folder export, read by
// GDAL's MVT driver, with the tile each came from ("x/y").
std::vector<std::pair<std::string, OgrLine>> zoom_features(const fs::path& out, int z) {
  std::vector<std::pair<std::string, OgrLine>> all;
  if (!fs::exists(out / std::to_string(z))) return all;
  for (const auto& e : fs::recursive_directory_iterator(out / std::to_string(z))) {
    if (e.path().extension() != ".pbf") continue;
    const std::string x = e.path().parent_path().filename().string(), y = e.path().stem().string();
    for (OgrLine& f : read_ogr(e.path().string(),
                               {"X=" + x, "Y=" + y, "Z=" + std::to_string(z), "CLIP=NO"}, "mvt_id"))
      all.emplace_back(x + "/" + y, std::move(f));
  }
  return all;
}

// The first symbol layer of a style on `source_layer`.
const tileformat::JsonValue* symbol_layer(const tileformat::JsonValue& style,
                                          const std::string& source_layer) {
  for (const auto& l : style.find("layers")->array())
    if (l.find("type")->string() == "symbol" && l.find("source-layer")->string() == source_layer)
      return &l;
  return nullptr;
}

}  // namespace

// The world's countries (world.gpkg) as an area package labelled by
// name_long, exported to a folder of MVT with a style: read back by GDAL's
// MVT driver, at every zoom 0..3 every polygon of a labelled country carries
// its label as `name`, and the layer `labels` holds exactly one point per
// country drawn at that zoom, across all the zoom's tiles (none repeated at
// a tile edge), inside its tile, within half a tile unit of the stored
// anchor, with its name and a rank that follows the priorities. The style
// reads the glyphs the export wrote beside it and writes the label points'
// names with their fontstack.
TEST(ExportMvt, AreaLabelsAreOnePointPerPolygonAndTheNames) {
  TempDir dir;
  const std::string pkg = (dir / "world.mbtiles").string(), out = (dir / "mvt").string();
  ASSERT_TRUE(run_all({vectorize() + " areas -q " + sample("world.gpkg").string() +
                           " --label-field name_long --max-zoom 3 -o " + pkg,
                       vectorize() + " export -q " + pkg + " -o " + out + " --style-json " +
                           (dir / "style.json").string()},
                      dir.path()));
  const std::map<int64_t, LabelRow> labels = label_rows(pkg, dir.path());
  ASSERT_EQ(labels.size(), 177u);
  const double half = 20037508.342789244;
  for (int z = 0; z <= 3; ++z) {
    const double tile_m = 2 * half / std::ldexp(1.0, z), unit = tile_m / 4096;
    std::set<int64_t> drawn;
    std::map<int64_t, int> points;
    std::map<int64_t, double> rank;
    size_t named = 0;
    for (const auto& [xy, f] : zoom_features(out, z)) {
      const auto label = labels.find(f.id);
      if (f.layer == "world") {
        drawn.insert(f.id);
        ASSERT_NE(label, labels.end()) << "country " << f.id << " has no label";
        ASSERT_TRUE(f.fields.count("name")) << "country " << f.id << " in tile " << z << "/" << xy;
        EXPECT_EQ(f.fields.at("name"), label->second.text);
        ++named;
        continue;
      }
      ASSERT_EQ(f.layer, "labels");
      ASSERT_NE(label, labels.end()) << "label point " << f.id;
      ++points[f.id];
      EXPECT_EQ(f.fields.at("name"), label->second.text);
      rank[f.id] = std::stod(f.fields.at("rank"));
      ASSERT_EQ(f.pts.size(), 1u);
      // The stored anchor (latitudes past the mercator's edge on it), and
      // the tile the point came from holds it.
      const double lat = std::clamp(label->second.lat, -85.0511287798066, 85.0511287798066);
      const double mx = label->second.lon / 180 * half,
                   my = std::log(std::tan((90 + lat) * kPi / 360)) / kPi * half;
      EXPECT_NEAR(f.pts[0].first, mx, unit) << label->second.text << " at zoom " << z;
      EXPECT_NEAR(f.pts[0].second, my, unit) << label->second.text << " at zoom " << z;
      const int x = std::stoi(xy.substr(0, xy.find('/'))),
                y = std::stoi(xy.substr(xy.find('/') + 1));
      EXPECT_GE(f.pts[0].first, -half + x * tile_m - unit) << label->second.text;
      EXPECT_LE(f.pts[0].first, -half + (x + 1) * tile_m + unit) << label->second.text;
      EXPECT_LE(f.pts[0].second, half - y * tile_m + unit) << label->second.text;
      EXPECT_GE(f.pts[0].second, half - (y + 1) * tile_m - unit) << label->second.text;
    }
    EXPECT_GT(named, 150u) << "zoom " << z;
    for (const int64_t id : drawn)
      EXPECT_EQ(points[id], 1) << labels.at(id).text << ": label points at zoom " << z;
    for (const auto& [id, n] : points)
      EXPECT_TRUE(drawn.count(id)) << labels.at(id).text << " labelled but not drawn at zoom " << z;
    // Ranks follow the priorities (larger first).
    std::vector<std::pair<double, int64_t>> by_rank;
    for (const auto& [id, r] : rank)
      by_rank.emplace_back(r, id);
    std::sort(by_rank.begin(), by_rank.end());
    for (size_t k = 1; k < by_rank.size(); ++k)
      EXPECT_GE(labels.at(by_rank[k - 1].second).priority, labels.at(by_rank[k].second).priority)
          << "rank " << by_rank[k].first;
    if (z == 3) {
      EXPECT_EQ(points.size(), labels.size()) << "every country at zoom 3";
    }
  }
  const auto style = tileformat::JsonValue::parse(read_file(dir / "style.json"));
  ASSERT_TRUE(style.find("glyphs")) << read_file(dir / "style.json");
  EXPECT_EQ(style.find("glyphs")->string(), "fonts/{fontstack}/{range}.pbf");
  const tileformat::JsonValue* labels_layer = symbol_layer(style, "labels");
  ASSERT_TRUE(labels_layer) << read_file(dir / "style.json");
  const tileformat::JsonValue* layout = labels_layer->find("layout");
  EXPECT_EQ(layout->find("text-field")->text(), R"(["get","name"])");
  EXPECT_EQ(layout->find("symbol-sort-key")->text(), R"(["get","rank"])");
  const std::string font = layout->find("text-font")->array().at(0).string();
  EXPECT_TRUE(fs::is_regular_file(dir / "fonts" / font / "0-255.pbf")) << font;
  EXPECT_EQ(labels_layer->find("paint")->find("text-halo-width")->number(), 1.5);
  const auto meta = tileformat::JsonValue::parse(read_file(fs::path(out) / "metadata.json"));
  bool listed = false;
  for (const auto& l : meta.find("vector_layers")->array())
    listed = listed || (l.find("id")->string() == "labels" &&
                        l.find("fields")->find("rank")->string() == "Number");
  EXPECT_TRUE(listed) << "the labels layer in vector_layers";
}

// Lines and places labelled by their "name" attribute: every line of the
// finest zoom GDAL's MVT driver reads carries its label as `name`, every
// place of its own too; the styles write them along the lines (line
// placement, upright, at most 45 degrees a character) and beside the
// places; a package without labels keeps a style without symbol layers.
TEST(ExportMvt, LinesAndPlacesCarryTheirLabelsAsName) {
  TempDir dir;
  std::ofstream(dir / "rivers.geojson")
      << R"({"type":"FeatureCollection","features":[)"
      << R"({"type":"Feature","properties":{"name":"Aare","kind":"river"},"geometry":{"type":"LineString","coordinates":[[7.0,46.9],[7.4,46.95],[7.9,47.3],[8.2,47.6]]}},)"
      << R"({"type":"Feature","properties":{"name":"Reuss","kind":"river"},"geometry":{"type":"LineString","coordinates":[[8.6,46.6],[8.5,47.0],[8.3,47.4]]}},)"
      << R"({"type":"Feature","properties":{"name":"","kind":"river"},"geometry":{"type":"LineString","coordinates":[[6.5,46.5],[7.0,46.6]]}}]})";
  std::ofstream(dir / "towns.csv") << "lon,lat,people,name\n7.45,46.95,134000,Bern\n"
                                      "8.54,47.37,421000,Zürich\n6.14,46.2,203000,Genève\n";
  const std::string lines = (dir / "rivers.mbtiles").string(),
                    towns = (dir / "towns.mbtiles").string();
  ASSERT_TRUE(run_all(
      {vectorize() + " lines -q " + (dir / "rivers.geojson").string() +
           " --label-field name --max-zoom 8 -o " + lines,
       vectorize() + " points -q " + (dir / "towns.csv").string() +
           " --xy lon,lat --fields people --label-field name --merge-px 0 --max-zoom 8 -o " + towns,
       vectorize() + " export -q " + lines + " -o " + (dir / "lines").string() + " --style-json " +
           (dir / "lines.json").string(),
       vectorize() + " export -q " + towns + " -o " + (dir / "towns").string() + " --style-json " +
           (dir / "towns.json").string()},
      dir.path()));
  for (const std::string name : {"rivers", "towns"}) {
    const std::map<int64_t, LabelRow> labels =
        label_rows((dir / (name + ".mbtiles")).string(), dir.path());
    ASSERT_EQ(labels.size(), name == "rivers" ? 2u : 3u) << name;
    std::set<int64_t> named;
    for (const auto& [xy, f] : zoom_features(dir / (name == "rivers" ? "lines" : "towns"), 8)) {
      const auto label = labels.find(f.id);
      if (label == labels.end()) {
        EXPECT_FALSE(f.fields.count("name") && !f.fields.at("name").empty())
            << name << " feature " << f.id << " is named without a label";
        continue;
      }
      ASSERT_TRUE(f.fields.count("name")) << name << " feature " << f.id << " in tile 8/" << xy;
      EXPECT_EQ(f.fields.at("name"), label->second.text);
      named.insert(f.id);
    }
    EXPECT_EQ(named.size(), labels.size()) << name;
  }
  const auto line_style = tileformat::JsonValue::parse(read_file(dir / "lines.json"));
  EXPECT_EQ(line_style.find("glyphs")->string(), "fonts/{fontstack}/{range}.pbf");
  const tileformat::JsonValue* along = symbol_layer(line_style, "rivers");
  ASSERT_TRUE(along) << read_file(dir / "lines.json");
  EXPECT_EQ(along->find("layout")->find("symbol-placement")->string(), "line");
  EXPECT_EQ(along->find("layout")->find("text-max-angle")->number(), 45);
  EXPECT_TRUE(along->find("layout")->find("text-keep-upright")->boolean());
  const auto point_style = tileformat::JsonValue::parse(read_file(dir / "towns.json"));
  const tileformat::JsonValue* beside = symbol_layer(point_style, "points");
  ASSERT_TRUE(beside) << read_file(dir / "towns.json");
  EXPECT_TRUE(beside->find("layout")->find("text-variable-anchor"));
  const std::string font = beside->find("layout")->find("text-font")->array().at(0).string();
  EXPECT_TRUE(fs::is_regular_file(dir / "fonts" / font / "0-255.pbf")) << font;
  // Without labels: no glyphs, no symbol layer, no fonts folder.
  const fs::path plain = dir / "plain";
  fs::create_directories(plain);
  ASSERT_TRUE(run_all({vectorize() + " lines -q " + (dir / "rivers.geojson").string() +
                           " --max-zoom 5 -o " + (plain / "r.mbtiles").string(),
                       vectorize() + " export -q " + (plain / "r.mbtiles").string() + " -o " +
                           (plain / "r").string() + " --style-json " + (plain / "r.json").string()},
                      dir.path()));
  const auto unlabelled = tileformat::JsonValue::parse(read_file(plain / "r.json"));
  EXPECT_FALSE(unlabelled.find("glyphs"));
  EXPECT_FALSE(symbol_layer(unlabelled, "rivers"));
  EXPECT_FALSE(fs::exists(plain / "fonts"));
}

// The same bytes for any thread count (the tiles are encoded in parallel and
// written in tile-id order).
TEST(ExportDem, SameBytesForAnyThreadCount) {
  const fs::path& d = surface_dem();
  TempDir dir;
  const std::string pkg = (d / "geodetic.mbtiles").string();
  std::string first;
  for (int threads : {1, 3}) {
    // The same name: it is the archive's name in its metadata.
    fs::create_directories(dir / ("j" + std::to_string(threads)));
    const std::string out = (dir / ("j" + std::to_string(threads)) / "out.pmtiles").string();
    ASSERT_EQ(run(tiler() + " export -q -j " + std::to_string(threads) + " " + pkg +
                      " --format terrarium -o " + out,
                  dir.path())
                  .exit_code,
              0);
    if (first.empty())
      first = read_file(out);
    else
      EXPECT_TRUE(read_file(out) == first) << "-j " << threads << " differs from -j 1";
  }
}
