// PNG encoding and decoding through libpng (see png_codec.hpp).
#include "runtime/png_codec.hpp"

#include <png.h>
#include <zlib.h>

#include <cstring>
#include <stdexcept>
#include <string>

namespace globe {
namespace {

struct WriteState {
  std::vector<uint8_t>* out;
  char error[200];
};

void on_write(png_structp png, png_bytep data, png_size_t n) {
  auto* st = static_cast<WriteState*>(png_get_io_ptr(png));
  st->out->insert(st->out->end(), data, data + n);
}
void on_flush(png_structp) {}
void on_error(png_structp png, png_const_charp msg) {
  auto* st = static_cast<WriteState*>(png_get_error_ptr(png));
  std::strncpy(st->error, msg, sizeof st->error - 1);
  png_longjmp(png, 1);
}
void on_warning(png_structp, png_const_charp) {}

// libpng reports errors by longjmp: this frame holds nothing with a destructor.
bool write_png(WriteState& st, const uint8_t* pixels, int width, int height, int channels,
               int effort, PngFilter filter) {
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &st, on_error, on_warning);
  if (!png) return false;
  png_infop info = png_create_info_struct(png);
  if (!info || setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, info ? &info : nullptr);
    return false;
  }
  static const int kColourType[] = {PNG_COLOR_TYPE_GRAY, PNG_COLOR_TYPE_GRAY_ALPHA,
                                    PNG_COLOR_TYPE_RGB, PNG_COLOR_TYPE_RGB_ALPHA};
  png_set_write_fn(png, &st, on_write, on_flush);
  png_set_IHDR(png, info, width, height, 8, kColourType[channels - 1], PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  if (filter == PngFilter::kUp) {
    png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_FILTER_UP);
    png_set_compression_level(png, effort);
    // libpng's default for filtered rows, Z_FILTERED, made these 6 % larger.
    png_set_compression_strategy(png, Z_DEFAULT_STRATEGY);
  } else if (effort <= 1) {
    png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_FILTER_PAETH);
    png_set_compression_level(png, 1);
    png_set_compression_strategy(png, Z_RLE);
  } else {
    png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_ALL_FILTERS);
    png_set_compression_level(png, effort);
  }
  png_write_info(png, info);
  const size_t stride = size_t(width) * channels;
  for (int y = 0; y < height; ++y)
    png_write_row(png, const_cast<png_bytep>(pixels + y * stride));
  png_write_end(png, info);
  png_destroy_write_struct(&png, &info);
  return true;
}

}  // namespace

std::vector<uint8_t> encode_png(const uint8_t* pixels, int width, int height, int channels,
                                int effort, PngFilter filter) {
  if (channels < 1 || channels > 4 || width < 1 || height < 1 || effort < 1 || effort > 9)
    throw std::invalid_argument("encode_png: " + std::to_string(width) + " x " +
                                std::to_string(height) + " pixels of " + std::to_string(channels) +
                                " channels at effort " + std::to_string(effort));
  std::vector<uint8_t> out;
  out.reserve(size_t(width) * height * channels / 2);
  WriteState st{&out, {}};
  if (!write_png(st, pixels, width, height, channels, effort, filter))
    throw std::runtime_error(std::string("PNG encoding failed: ") +
                             (st.error[0] ? st.error : "out of memory"));
  return out;
}

std::vector<uint8_t> decode_png_rgba(const uint8_t* data, size_t size, int& width, int& height) {
  png_image image;
  std::memset(&image, 0, sizeof image);
  image.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_memory(&image, data, size))
    throw std::runtime_error(std::string("not a readable PNG (") + image.message + ")");
  image.format = PNG_FORMAT_RGBA;
  std::vector<uint8_t> out(PNG_IMAGE_SIZE(image));
  if (!png_image_finish_read(&image, nullptr, out.data(), 0, nullptr)) {
    const std::string why = image.message;
    png_image_free(&image);
    throw std::runtime_error("PNG decoding failed (" + why + ")");
  }
  width = static_cast<int>(image.width);
  height = static_cast<int>(image.height);
  return out;
}

}  // namespace globe
