// glibc allocator settings (see heap_tuning.hpp).
#include "kit/heap_tuning.hpp"

#include <malloc.h>

#include <algorithm>
#include <thread>

namespace globe {

void keep_tile_buffers_in_heap() {
  mallopt(M_MMAP_THRESHOLD, 64 << 20);
  mallopt(M_TRIM_THRESHOLD, 256 << 20);
}

void reuse_large_arrays() {
  mallopt(M_ARENA_MAX, 1);
  mallopt(M_MMAP_MAX, 0);
  mallopt(M_TRIM_THRESHOLD, -1);  // never
}

void one_heap_per_core() {
  mallopt(M_ARENA_MAX, int(std::max(1u, std::thread::hardware_concurrency())));
}

}  // namespace globe
