// libFuzzer target: analysis blocks (see fuzz_entries.hpp).
#include "fuzz_entries.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  globe_fuzz::analysis_block({data, size});
  return 0;
}
