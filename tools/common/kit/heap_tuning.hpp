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
// freed array's pages serve the next one without faulting again. The heap's
// peak is the peak of live arrays, as before; it is not given back until the
// process ends. (No transparent huge pages: on virtual machines that hand
// freed memory back to their host, a huge page faulted in costs 5 times as
// much as its 512 small ones: docs/analysis.md, "Flow: memory".)
void reuse_large_arrays();

// For a server whose worker threads outnumber the cores (globe-serve): at
// most one heap per core instead of glibc's eight. Each thread that allocates
// gets an arena of its own up to that cap, and what a request freed in one is
// kept there for that arena's next user: with 64 threads, 100 clients asking
// new terrain tiles held 525 MB against 325 MB with two arenas (issue 55,
// docs/serve.md "Under load"); no thread allocates faster than a core runs.
void one_heap_per_core();

}  // namespace globe
