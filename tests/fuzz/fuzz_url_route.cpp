// libFuzzer target: globe-serve request paths (see fuzz_entries.hpp).
#include "fuzz_entries.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  globe_fuzz::url_route({data, size});
  return 0;
}
