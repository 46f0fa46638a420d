// PNG output (see image_file.hpp).
#include "app/image_file.hpp"

#include <gdal.h>

#include <cstdio>
#include <filesystem>

#include "errors.hpp"
#include "gdal_dataset.hpp"

namespace globe::viewer {

void write_png(const std::string& path, const std::vector<uint8_t>& rgba, int width, int height) {
  gdal_init();
  const std::string tmp = path + ".tmp.png";
  GdalDataset mem(GDALCreate(GDALGetDriverByName("MEM"), "", width, height, 3, GDT_Byte, nullptr),
                  "in-memory image");
  if (!mem.get()) throw OutputError(path + ": cannot create an in-memory image");
  for (int b = 0; b < 3; ++b)
    if (GDALRasterIO(mem.band(b + 1), GF_Write, 0, 0, width, height,
                     const_cast<uint8_t*>(rgba.data()) + b, width, height, GDT_Byte, 4,
                     width * 4) != CE_None)
      throw OutputError(path + ": cannot fill the in-memory image");
  {
    GdalDataset png(GDALCreateCopy(GDALGetDriverByName("PNG"), tmp.c_str(), mem.get(), FALSE,
                                   nullptr, nullptr, nullptr),
                    tmp);
    if (!png.get()) {
      std::remove(tmp.c_str());
      throw OutputError(path + ": cannot write PNG (" + CPLGetLastErrorMsg() + ")");
    }
  }
  std::remove((tmp + ".aux.xml").c_str());
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    std::remove(tmp.c_str());
    throw OutputError(path + ": cannot rename the finished image into place: " + ec.message());
  }
}

}  // namespace globe::viewer
