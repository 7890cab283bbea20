#include "client/malloc_policy.h"

#include <malloc.h>

namespace membrane::client {

void UseClientMallocPolicy() {
  // One arena: `reconstruct --local` checks the mesh on a second thread while it encodes;
  // with an arena of its own that thread would fault in fresh pages instead of reusing what
  // the earlier stages freed (on rocker-arm-scan the check takes 0.23 s with one arena and
  // 0.36 s with glibc's default, the whole run 1.05 s and 1.27 s). Two threads hardly contend
  // for one arena.
  mallopt(M_ARENA_MAX, 1);
  // No blocks mapped on their own (glibc maps every block of 32 MB and more and unmaps it when
  // freed) and no trim (-1 turns it off): each stage's grid-sized arrays then reuse the pages
  // the stage before freed, where fresh ones are cleared by the kernel and, on a VM that
  // reports free pages to its host, faulted in by the host again.
  mallopt(M_MMAP_MAX, 0);
  mallopt(M_TRIM_THRESHOLD, -1);
}

}  // namespace membrane::client
