// Process-wide settings of glibc's allocator for the tools' working arrays
// (docs/analysis.md, "Flow: memory"). Call before any worker thread starts.
#pragma once

#include <cstdint>

namespace globe {

// The builders' per-tile buffers (blocks of 257^2 samples, warp windows) are
// a few hundred KiB each, allocated and freed per tile: served from mmap by
// default, every one of them page-faults afresh. Kept in the heap (and the
// heap not trimmed after each), they are reused.
void keep_tile_buffers_in_heap();

// For work whose buffers are arrays of many megabytes allocated and freed per
// chunk and per pass by every worker (the flow solver): one heap for all
// threads, never returned to the system, no array in its own mapping, so a
// freed array's pages serve the next one without faulting again; and the
// first `reserve_bytes` of that heap advised for transparent huge pages
// (where the kernel offers them on request), a 2 MiB fault instead of 512.
// The heap's peak is the peak of live arrays, as before; it is not given
// back until the process ends.
void reuse_large_arrays(uint64_t reserve_bytes);

}  // namespace globe
