// libFuzzer target: area_tile blobs (see fuzz_entries.hpp).
#include "fuzz_entries.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  globe_fuzz::area_tile({data, size});
  return 0;
}
