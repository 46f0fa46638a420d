// Text files (see text_file.hpp).
#include "app/text_file.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "runtime/errors.hpp"

namespace globe::viewer {

void write_text_file(const std::string& path, const std::string& text) {
  const std::string tmp = path + ".tmp";
  std::FILE* f = std::fopen(tmp.c_str(), "wb");
  if (!f)
    throw OutputError(path + ": cannot create " + tmp + " (" + std::strerror(errno) +
                      "); check the folder exists and is writable");
  const bool ok = std::fwrite(text.data(), 1, text.size(), f) == text.size();
  if (std::fclose(f) != 0 || !ok) {
    std::remove(tmp.c_str());
    throw OutputError(path + ": cannot write " + tmp + " (disk full?)");
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    std::remove(tmp.c_str());
    throw OutputError(path + ": cannot rename the finished file into place: " + ec.message());
  }
}

}  // namespace globe::viewer
