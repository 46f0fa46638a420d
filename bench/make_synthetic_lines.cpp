// Writes synthetic river-like lines for benchmarks: LINES random walks of
// VERTICES vertices each over Europe (EPSG:4326), with a Real attribute
// `upArea` like efas_rivers, as FlatGeobuf. Deterministic (fixed-seed
// generator); features are streamed, so memory stays small for any size.
// Usage: make_synthetic_lines LINES VERTICES OUT.fgb
#include <gdal.h>
#include <ogr_api.h>
#include <ogr_srs_api.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>

int main(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: make_synthetic_lines LINES VERTICES OUT.fgb\n");
    return 2;
  }
  const long lines = std::atol(argv[1]);
  const int vertices = std::atoi(argv[2]);
  if (lines < 1 || vertices < 2) {
    std::fprintf(stderr, "make_synthetic_lines: LINES >= 1 and VERTICES >= 2\n");
    return 2;
  }
  GDALAllRegister();
  GDALDriverH driver = GDALGetDriverByName("FlatGeobuf");
  GDALDatasetH ds = driver ? GDALCreate(driver, argv[3], 0, 0, 0, GDT_Unknown, nullptr) : nullptr;
  if (!ds) {
    std::fprintf(stderr, "make_synthetic_lines: cannot create %s\n", argv[3]);
    return 1;
  }
  OGRSpatialReferenceH srs = OSRNewSpatialReference(nullptr);
  OSRImportFromEPSG(srs, 4326);
  OGRLayerH layer = GDALDatasetCreateLayer(ds, "lines", srs, wkbLineString, nullptr);
  OSRRelease(srs);
  OGRFieldDefnH fd = OGR_Fld_Create("upArea", OFTReal);
  OGR_L_CreateField(layer, fd, TRUE);
  OGR_Fld_Destroy(fd);
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> lon(-10, 40), lat(36, 70), turn(-0.6, 0.6), area(1, 1e6);
  for (long i = 0; i < lines; ++i) {
    OGRFeatureH f = OGR_F_Create(OGR_L_GetLayerDefn(layer));
    OGR_F_SetFieldDouble(f, 0, area(rng));
    OGRGeometryH g = OGR_G_CreateGeometry(wkbLineString);
    double x = lon(rng), y = lat(rng), heading = turn(rng) * 10;
    for (int v = 0; v < vertices; ++v) {
      OGR_G_AddPoint_2D(g, x, y);
      heading += turn(rng);
      x += 0.01 * std::cos(heading);  // ~1 km steps
      y += 0.01 * std::sin(heading);
    }
    OGR_F_SetGeometryDirectly(f, g);
    if (OGR_L_CreateFeature(layer, f) != OGRERR_NONE) {
      std::fprintf(stderr, "make_synthetic_lines: write failed\n");
      return 1;
    }
    OGR_F_Destroy(f);
  }
  GDALClose(ds);
  return 0;
}
