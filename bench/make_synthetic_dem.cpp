// Writes a synthetic DEM for benchmarks: Int16 GeoTIFF (tiled, DEFLATE), UTM
// zone 32N, 10 m pixels, ridged multi-octave terrain from a hash-based value
// noise (deterministic). Rows are generated and written in strips, so memory
// stays small for any size. Usage: make_synthetic_dem SIZE OUT.tif [STRETCH]
// STRETCH (default 1) scales the noise's frequencies: 16 puts relief of
// hundreds of metres between neighbouring samples, like a global 5' DEM's
// mountains (bench/make_global.sh --relief adds it to the smooth grid).
#include <cpl_string.h>
#include <gdal.h>
#include <ogr_srs_api.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <vector>

namespace {

double lattice(int64_t x, int64_t y) {
  uint64_t h = static_cast<uint64_t>(x) * 0x9E3779B97F4A7C15ull ^
               static_cast<uint64_t>(y) * 0xC2B2AE3D27D4EB4Full;
  h ^= h >> 31;
  h *= 0xBF58476D1CE4E5B9ull;
  h ^= h >> 29;
  return static_cast<double>(h >> 11) / static_cast<double>(1ull << 53);
}

double value_noise(double x, double y) {
  const int64_t x0 = static_cast<int64_t>(std::floor(x)), y0 = static_cast<int64_t>(std::floor(y));
  const double fx = x - x0, fy = y - y0;
  const double sx = fx * fx * (3 - 2 * fx), sy = fy * fy * (3 - 2 * fy);
  const double a = lattice(x0, y0), b = lattice(x0 + 1, y0), c = lattice(x0, y0 + 1),
               d = lattice(x0 + 1, y0 + 1);
  return (a + (b - a) * sx) + ((c + (d - c) * sx) - (a + (b - a) * sx)) * sy;
}

double terrain(double x, double y, double stretch) {
  double h = 0, amp = 1200, freq = stretch / 2048;
  for (int o = 0; o < 9; ++o) {
    h += amp * (1 - std::abs(2 * value_noise(x * freq, y * freq) - 1));
    amp *= 0.45;
    freq *= 2;
  }
  return h;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3 && argc != 4) {
    std::fprintf(stderr, "usage: make_synthetic_dem SIZE OUT.tif [STRETCH]\n");
    return 2;
  }
  const int size = std::atoi(argv[1]);
  const double stretch = argc == 4 ? std::atof(argv[3]) : 1.0;
  GDALAllRegister();
  char** opts = nullptr;
  opts = CSLSetNameValue(opts, "TILED", "YES");
  opts = CSLSetNameValue(opts, "COMPRESS", "DEFLATE");
  opts = CSLSetNameValue(opts, "ZLEVEL", "1");
  opts = CSLSetNameValue(opts, "BIGTIFF", "IF_SAFER");
  GDALDatasetH ds =
      GDALCreate(GDALGetDriverByName("GTiff"), argv[2], size, size, 1, GDT_Int16, opts);
  CSLDestroy(opts);
  if (!ds) {
    std::fprintf(stderr, "cannot create %s\n", argv[2]);
    return 1;
  }
  double gt[6] = {400000, 10, 0, 5300000, 0, -10};
  GDALSetGeoTransform(ds, gt);
  OGRSpatialReferenceH srs = OSRNewSpatialReference(nullptr);
  OSRImportFromEPSG(srs, 32632);
  GDALSetSpatialRef(ds, srs);
  OSRRelease(srs);
  const int strip = 256;
  std::vector<int16_t> buf(static_cast<size_t>(size) * strip);
  for (int y0 = 0; y0 < size; y0 += strip) {
    const int rows = std::min(strip, size - y0);
    for (int r = 0; r < rows; ++r)
      for (int x = 0; x < size; ++x)
        buf[static_cast<size_t>(r) * size + x] = static_cast<int16_t>(terrain(x, y0 + r, stretch));
    if (GDALRasterIO(GDALGetRasterBand(ds, 1), GF_Write, 0, y0, size, rows, buf.data(), size, rows,
                     GDT_Int16, 0, 0) != CE_None) {
      std::fprintf(stderr, "write failed\n");
      return 1;
    }
  }
  GDALClose(ds);
  return 0;
}
