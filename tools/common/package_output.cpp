// Package creation and commit (see package_output.hpp).
#include "package_output.hpp"

#include <filesystem>

#include "errors.hpp"
#include "tileformat/error.hpp"

namespace globe {

std::unique_ptr<tileformat::PackageWriter> create_package(const std::string& path, bool force) {
  try {
    return std::make_unique<tileformat::PackageWriter>(path, force);
  } catch (const tileformat::PackageError& e) {
    throw OutputError(e.what());
  }
}

uint64_t commit_package(tileformat::PackageWriter& writer, const std::string& path) {
  try {
    writer.commit();
  } catch (const tileformat::PackageError& e) {
    throw OutputError(e.what());
  }
  std::error_code ec;
  const auto bytes = std::filesystem::file_size(path, ec);
  return ec ? 0 : bytes;
}

}  // namespace globe
