#include "core/base/malloc_policy.h"

#include <malloc.h>

namespace membrane {

void KeepFreedBlocksInOneHeap() {
  // One arena: glibc gives a new thread an arena of its own, and only the main arena's heap
  // can hold a block of more than 64 MB; in another arena such a block is mapped on its own
  // whatever M_MMAP_MAX says. A job's thread would fault in fresh pages for every grid-sized
  // array, and the check's thread beside the encode for its tables (on rocker-arm-scan the
  // check takes 0.23 s with one arena and 0.36 s with glibc's default). Threads hardly
  // contend for it: their small blocks come from per-thread caches, and the big ones are few.
  mallopt(M_ARENA_MAX, 1);
  // No blocks mapped on their own (glibc maps every block of 32 MB and more and unmaps it when
  // freed) and no trim (-1 turns it off): each stage's grid-sized arrays then reuse the pages
  // the stage before freed, where fresh ones are cleared by the kernel and, on a VM that
  // reports free pages to its host, faulted in by the host again.
  mallopt(M_MMAP_MAX, 0);
  mallopt(M_TRIM_THRESHOLD, -1);
}

}  // namespace membrane
