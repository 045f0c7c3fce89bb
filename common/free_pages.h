// free_pages.h: hands the pages the allocator holds free back to the system between the build's steps.
//
// glibc's malloc keeps freed memory in the arena of the thread that freed it, and after the first large
// free it raises its trim threshold to twice that block, so an arena may hold tens of megabytes that
// other threads' allocations never reuse: the file's text and repair's copies stay resident in the main
// arena through the DAG while the workers take new pages in theirs, and the rounds' scratch stays in
// the workers' arenas while the main thread lays out the file. malloc_trim(0) gives back every whole
// free page of every arena (madvise, not only each heap's top). It costs the page faults of the pages
// used again: nothing measurable on two threads, where it takes a sixth off a 0.8 M-triangle build's
// peak, but 4-5% of the DAG on 16, where faults on many threads contend, for 8-20 MB; on one thread
// the main arena reuses everything (CHANGELOG.md, 2026-12-01). The memory is a fixed 20-40 MB: from a
// few million triangles up it is no share of the peak worth the faults.
#pragma once

#if defined(__GLIBC__)
#include <malloc.h>
#endif

#include "stage_times.h"

namespace vgeo {

constexpr int kFreePagesMostThreads = 4;  // above it the faults of reusing the pages cost more than they save

inline void returnFreePages(int threads, StageTimes* times) {
#if defined(__GLIBC__)
  if (threads <= 1 || threads > kFreePagesMostThreads) return;
  StageTimer timer(times, "free pages");
  malloc_trim(0);
#endif
}

}  // namespace vgeo
