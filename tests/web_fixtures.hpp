// Helpers of the web export tests: PNG pixels through GDAL's PNG driver (an
// independent decoder), and running a page of tests/web/pages in headless
// chromium (tests/web/README.md).
#pragma once

#include <string>
#include <vector>

#include <cpl_vsi.h>
#include <gdal.h>

#include "raster_fixtures.hpp"
#include "test_paths.hpp"
#include "test_support.hpp"

namespace globe_test {

// RGB pixels of a PNG in memory (GDAL's PNG driver).
// The first `channels` bands of a PNG in memory (GDAL's decoder), interleaved.
inline std::vector<uint8_t> png_pixels(const std::string& bytes, int& w, int& h, int channels) {
  gdal_setup();
  static int serial = 0;
  const std::string name = "/vsimem/web_export_" + std::to_string(++serial) + ".png";
  VSIFCloseL(VSIFileFromMemBuffer(name.c_str(),
                                  reinterpret_cast<GByte*>(const_cast<char*>(bytes.data())),
                                  vsi_l_offset(bytes.size()), FALSE));
  GDALDatasetH ds = GDALOpen(name.c_str(), GA_ReadOnly);
  std::vector<uint8_t> px;
  if (ds && GDALGetRasterCount(ds) >= channels) {
    w = GDALGetRasterXSize(ds), h = GDALGetRasterYSize(ds);
    px.resize(size_t(w) * h * channels);
    int bands[4] = {1, 2, 3, 4};
    if (GDALDatasetRasterIO(ds, GF_Read, 0, 0, w, h, px.data(), w, h, GDT_Byte, channels, bands,
                            channels, size_t(w) * channels, 1) != CE_None)
      px.clear();
  }
  if (ds) GDALClose(ds);
  VSIUnlink(name.c_str());
  return px;
}
inline std::vector<uint8_t> png_rgb(const std::string& bytes, int& w, int& h) {
  return png_pixels(bytes, w, h, 3);
}

// Runs tests/web/pages/PAGE (or PAGE itself if it is an http:// URL) with
// /data serving `data` and the query string; installs the browser and the
// npm packages first if missing.
inline RunResult run_web_page(const std::string& page, const fs::path& data,
                              const std::string& query, const fs::path& screenshot,
                              const fs::path& scratch, const std::string& viewport = "800x600") {
  const std::string web = globe_test::paths::test_data_dir() + "/../web";
  const RunResult cache =
      run(globe_test::paths::test_data_dir() + "/../../scripts/web-deps.sh", scratch);
  if (cache.exit_code != 0) return cache;
  const std::string dir = cache.out.substr(0, cache.out.find_last_not_of('\n') + 1);
  return run("GLOBE_WEB_CACHE=" + dir + " node " + web + "/run_page.mjs --timeout 90 --viewport " +
                 viewport + " --mount /data=" + data.string() + " --query '" + query +
                 "' --screenshot " + screenshot.string() + " " +
                 (page.rfind("http://", 0) == 0 ? page : web + "/pages/" + page),
             scratch);
}

}  // namespace globe_test
