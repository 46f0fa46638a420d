// JPEG and WebP decoding (see jpeg_webp_decoders.hpp).
#include "runtime/jpeg_webp_decoders.hpp"

#include <csetjmp>
#include <cstdio>
#include <stdexcept>
#include <string>

// jpeglib.h needs FILE and size_t declared first.
#include <jpeglib.h>
#include <webp/decode.h>

namespace globe {
namespace {

struct JpegError {
  jpeg_error_mgr mgr;
  std::jmp_buf jump;
  char message[JMSG_LENGTH_MAX];
};

void on_jpeg_error(j_common_ptr info) {
  auto* err = reinterpret_cast<JpegError*>(info->err);
  (*info->err->format_message)(info, err->message);
  std::longjmp(err->jump, 1);
}

void on_jpeg_message(j_common_ptr, int) {}  // warnings: ignored

}  // namespace

std::vector<uint8_t> decode_jpeg_rgba(const uint8_t* data, size_t size, int& width, int& height) {
  jpeg_decompress_struct info;
  JpegError err;
  info.err = jpeg_std_error(&err.mgr);
  err.mgr.error_exit = on_jpeg_error;
  err.mgr.emit_message = on_jpeg_message;
  err.message[0] = 0;
  // Everything the error path touches is declared before setjmp.
  std::vector<uint8_t> out;
  if (setjmp(err.jump)) {
    jpeg_destroy_decompress(&info);
    throw std::runtime_error(std::string("JPEG decoding failed (") + err.message + ")");
  }
  jpeg_create_decompress(&info);
  jpeg_mem_src(&info, data, static_cast<unsigned long>(size));
  jpeg_read_header(&info, TRUE);
  info.out_color_space = JCS_EXT_RGBA;
  jpeg_start_decompress(&info);
  width = static_cast<int>(info.output_width);
  height = static_cast<int>(info.output_height);
  out.resize(size_t(width) * height * 4);
  while (info.output_scanline < info.output_height) {
    JSAMPROW row = out.data() + size_t(info.output_scanline) * width * 4;
    jpeg_read_scanlines(&info, &row, 1);
  }
  jpeg_finish_decompress(&info);
  jpeg_destroy_decompress(&info);
  return out;
}

std::vector<uint8_t> decode_webp_rgba(const uint8_t* data, size_t size, int& width, int& height) {
  if (!WebPGetInfo(data, size, &width, &height))
    throw std::runtime_error("not a readable WebP image");
  std::vector<uint8_t> out(size_t(width) * height * 4);
  if (!WebPDecodeRGBAInto(data, size, out.data(), out.size(), width * 4))
    throw std::runtime_error("WebP decoding failed");
  return out;
}

}  // namespace globe
