// libFuzzer target: package files (see fuzz_entries.hpp). The bytes go to a
// scratch file in /dev/shm (or the working folder) that SQLite then opens.
#include <unistd.h>

#include <filesystem>
#include <string>

#include "fuzz_entries.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const std::string path =
      (std::filesystem::is_directory("/dev/shm") ? std::string("/dev/shm/") : std::string("./")) +
      "globe-fuzz-package-" + std::to_string(::getpid()) + ".mbtiles";
  globe_fuzz::package({data, size}, path);
  return 0;
}
