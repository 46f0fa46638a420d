// PNG output (see image_file.hpp).
#include "app/image_file.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <stdexcept>

#include "runtime/errors.hpp"
#include "runtime/png_codec.hpp"

namespace globe::viewer {
namespace {
constexpr int kPngEffort = 6;  // snapshots are small; adaptive filters make them smaller
}

void write_png(const std::string& path, const std::vector<uint8_t>& rgba, int width, int height) {
  std::vector<uint8_t> rgb(size_t(width) * height * 3);
  for (size_t i = 0, n = size_t(width) * height; i < n; ++i)
    std::memcpy(&rgb[3 * i], &rgba[4 * i], 3);
  std::vector<uint8_t> png;
  try {
    png = encode_png(rgb.data(), width, height, 3, kPngEffort);
  } catch (const std::runtime_error& e) {
    throw OutputError(path + ": cannot encode PNG (" + e.what() + ")");
  }
  const std::string tmp = path + ".tmp.png";
  std::FILE* f = std::fopen(tmp.c_str(), "wb");
  if (!f)
    throw OutputError(path + ": cannot create " + tmp + " (" + std::strerror(errno) +
                      "); check the folder exists and is writable");
  const bool written = std::fwrite(png.data(), 1, png.size(), f) == png.size();
  const int write_errno = errno;
  if (std::fclose(f) != 0 || !written) {
    std::remove(tmp.c_str());
    throw OutputError(path + ": cannot write the image (" + std::strerror(write_errno) +
                      "); check free space");
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    std::remove(tmp.c_str());
    throw OutputError(path + ": cannot rename the finished image into place: " + ec.message());
  }
}

}  // namespace globe::viewer
