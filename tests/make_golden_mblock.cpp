// Writes tests/data/golden_mblock_v1.bin (run only when a new format version
// gets its own golden file; version 1 blobs must keep decoding forever).
#include <cstdio>
#include <fstream>

#include "golden_block.hpp"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: make_golden_mblock OUT.bin\n");
    return 2;
  }
  const auto blob = tileformat::encode_mblock(golden_block());
  std::ofstream out(argv[1], std::ios::binary);
  out.write(reinterpret_cast<const char*>(blob.data()), static_cast<std::streamsize>(blob.size()));
  return out ? 0 : 1;
}
