// free_pages.h: hands the pages the allocator holds free back to the system between the build's steps.
//
// glibc's malloc keeps freed memory in the arena of the thread that freed it, and after the first large
// free it raises its trim threshold to twice that block, so an arena may hold tens of megabytes that
// other threads' allocations never reuse: the file's text and repair's copies stay resident through the
// DAG, the leaf partition's scratch through the rounds, the rounds' scratch in the workers' arenas while
// the main thread lays out the file. malloc_trim(0) gives back every whole free page of every arena
// (madvise, not only each heap's top). Called where a large step's temporaries have just died, it costs
// a walk of the arenas' free lists and the page faults of the pages used again; on one thread the main
// arena reuses all of it, so nothing is given back. Lower fixed malloc thresholds instead made every
// large array a fresh mapping and cost up to a fifth of the DAG on 16 threads (bench/build.md).
#pragma once

#if defined(__GLIBC__)
#include <malloc.h>
#endif

#include "stage_times.h"

namespace vgeo {

inline void returnFreePages(int threads, StageTimes* times) {
#if defined(__GLIBC__)
  if (threads <= 1) return;
  StageTimer timer(times, "free pages");
  malloc_trim(0);
#endif
}

}  // namespace vgeo
