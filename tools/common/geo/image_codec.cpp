// Image tile encoding (PNG through libpng, JPEG and WebP through GDAL) and
// decoding through GDAL (see image_codec.hpp).
#include "geo/image_codec.hpp"

#include <cpl_string.h>
#include <cpl_vsi.h>
#include <gdal.h>

#include <algorithm>
#include <atomic>
#include <numeric>
#include <string>

#include "geo/gdal_dataset.hpp"
#include "runtime/png_codec.hpp"
#include "tileformat/error.hpp"

namespace globe {
namespace {

std::string memory_file_name(const char* ext) {
  static std::atomic<uint64_t> counter{0};
  return "/vsimem/globe_image_" + std::to_string(counter.fetch_add(1)) + "." + ext;
}

// Unlinks an in-memory file when it goes out of scope.
struct MemoryFile {
  std::string name;
  ~MemoryFile() { VSIUnlink(name.c_str()); }
};

}  // namespace

bool TilePixels::empty() const {
  const uint8_t* a = alpha();
  return std::all_of(a, a + plane_size(), [](uint8_t v) { return v == 0; });
}

bool TilePixels::opaque() const {
  const uint8_t* a = alpha();
  return std::all_of(a, a + plane_size(), [](uint8_t v) { return v == 255; });
}

std::vector<uint8_t> encode_image_tile(const TilePixels& px, const EncodeOptions& options) {
  using tileformat::ImageFormat;
  gdal_init();
  const bool opaque = px.opaque();
  ImageFormat format = options.format;
  if (format == ImageFormat::kJpeg && !opaque) format = ImageFormat::kPng;
  // Planes to write, in order.
  std::vector<int> planes;
  for (int c = 0; c < px.colour; ++c)
    planes.push_back(c);
  if (format == ImageFormat::kWebp && px.colour == 1) planes = {0, 0, 0};
  if (!opaque) planes.push_back(px.colour);

  if (format == ImageFormat::kPng) {
    const int channels = static_cast<int>(planes.size());
    std::vector<uint8_t> interleaved(px.plane_size() * channels);
    for (int c = 0; c < channels; ++c) {
      const uint8_t* src = px.plane(planes[c]);
      for (size_t i = 0; i < px.plane_size(); ++i)
        interleaved[i * channels + c] = src[i];
    }
    return encode_png(interleaved.data(), px.size, px.size, channels, options.png_level);
  }

  GDALDriverH mem = GDALGetDriverByName("MEM");
  GdalDataset ds(
      GDALCreate(mem, "", px.size, px.size, static_cast<int>(planes.size()), GDT_Byte, nullptr),
      "tile");
  if (!ds.get()) throw std::runtime_error("cannot create an image buffer: " + gdal_last_error());
  for (size_t b = 0; b < planes.size(); ++b) {
    if (GDALRasterIO(ds.band(static_cast<int>(b) + 1), GF_Write, 0, 0, px.size, px.size,
                     const_cast<uint8_t*>(px.plane(planes[b])), px.size, px.size, GDT_Byte, 0,
                     0) != CE_None)
      throw std::runtime_error("cannot fill an image buffer: " + gdal_last_error());
  }
  if (!opaque)
    gdal_check(
        GDALSetRasterColorInterpretation(ds.band(static_cast<int>(planes.size())), GCI_AlphaBand),
        "marking the tile's alpha band");

  const char* driver = format == ImageFormat::kJpeg ? "JPEG" : "WEBP";
  char** opts = nullptr;
  const std::string quality = std::to_string(options.quality);
  if (format == ImageFormat::kJpeg) opts = CSLSetNameValue(opts, "QUALITY", quality.c_str());
  if (format == ImageFormat::kWebp) {
    if (options.quality >= 100)
      opts = CSLSetNameValue(opts, "LOSSLESS", "YES");
    else
      opts = CSLSetNameValue(opts, "QUALITY", quality.c_str());
  }
  opts = CSLSetNameValue(opts, "WRITE_METADATA_AS_TEXT", "NO");
  MemoryFile file{memory_file_name(tileformat::image_format_name(format))};
  CPLErrorReset();
  GDALDatasetH out = GDALCreateCopy(GDALGetDriverByName(driver), file.name.c_str(), ds.get(), FALSE,
                                    opts, nullptr, nullptr);
  CSLDestroy(opts);
  if (!out)
    throw std::runtime_error(std::string(driver) + " encoding failed: " + gdal_last_error());
  GDALClose(out);
  vsi_l_offset length = 0;
  GByte* data = VSIGetMemFileBuffer(file.name.c_str(), &length, FALSE);
  if (!data || length == 0) throw std::runtime_error(std::string(driver) + " wrote no bytes");
  return std::vector<uint8_t>(data, data + length);
}

TilePixels decode_image_tile(std::span<const uint8_t> blob, int size, int colour) {
  gdal_init();
  const tileformat::ImageHeader header = tileformat::inspect_image_tile(blob);
  if (header.width != size || header.height != size)
    throw tileformat::FormatError("8", "image tile is " + std::to_string(header.width) + " x " +
                                           std::to_string(header.height) + " pixels, not " +
                                           std::to_string(size) + " x " + std::to_string(size));
  MemoryFile file{memory_file_name(tileformat::image_format_name(header.format))};
  VSILFILE* f =
      VSIFileFromMemBuffer(file.name.c_str(), const_cast<GByte*>(blob.data()), blob.size(), FALSE);
  if (!f) throw std::runtime_error("cannot map an image tile in memory");
  VSIFCloseL(f);
  const char* const drivers[] = {"PNG", "JPEG", "WEBP", nullptr};
  CPLErrorReset();
  GdalDataset ds(
      GDALOpenEx(file.name.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY, drivers, nullptr, nullptr),
      "tile");
  if (!ds.get())
    throw tileformat::FormatError("8", "image tile cannot be decoded (" + gdal_last_error() + ")");
  const int n = ds.bands();
  const bool has_alpha = n == 2 || n == 4;  // gray + alpha, RGBA
  const int native_colour = n - (has_alpha ? 1 : 0);
  if (native_colour != 1 && native_colour != 3)
    throw tileformat::FormatError("8", "image tile has " + std::to_string(n) + " bands");
  // Gray WebP tiles are stored as RGB (WebP has no gray): take the first band.
  if (native_colour == 3 && colour == 1 && header.format != tileformat::ImageFormat::kWebp)
    throw tileformat::FormatError("8", "image tile is in colour but the package is gray");
  TilePixels px(size, colour);
  auto read = [&](int band, uint8_t* dst) {
    if (GDALRasterIO(ds.band(band), GF_Read, 0, 0, size, size, dst, size, size, GDT_Byte, 0, 0) !=
        CE_None)
      throw tileformat::FormatError(
          "8", "image tile pixels cannot be decoded (" + gdal_last_error() + ")");
  };
  for (int c = 0; c < colour; ++c)
    read(native_colour == 1 ? 1 : c + 1, px.plane(c));
  if (has_alpha)
    read(n, px.plane(colour));
  else
    std::fill_n(px.plane(colour), px.plane_size(), uint8_t{255});
  return px;
}

}  // namespace globe
