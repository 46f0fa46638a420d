// glibc allocator settings (see heap_tuning.hpp).
#include "heap_tuning.hpp"

#include <malloc.h>
#include <sys/mman.h>

#include <cstdlib>

namespace globe {

void keep_tile_buffers_in_heap() {
  mallopt(M_MMAP_THRESHOLD, 64 << 20);
  mallopt(M_TRIM_THRESHOLD, 256 << 20);
}

void reuse_large_arrays([[maybe_unused]] uint64_t reserve_bytes) {
  mallopt(M_ARENA_MAX, 1);
  mallopt(M_MMAP_MAX, 0);
  mallopt(M_TRIM_THRESHOLD, -1);  // never
#if !defined(__SANITIZE_ADDRESS__)
  // Grow the heap by the reserve once (address space only: nothing is
  // touched), advise it, and give it back to the heap's free top, where the
  // arrays will be carved from.
  constexpr uintptr_t kHuge = uintptr_t(2) << 20;
  if (reserve_bytes < 2 * kHuge) return;
  void* block = std::malloc(size_t(reserve_bytes));
  if (!block) return;
  const uintptr_t begin = (uintptr_t(block) + kHuge - 1) & ~(kHuge - 1);
  const uintptr_t end = (uintptr_t(block) + reserve_bytes) & ~(kHuge - 1);
  if (end > begin) madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);
  std::free(block);
#endif
}

}  // namespace globe
