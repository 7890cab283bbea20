// membraned's memory between jobs: while a job runs, the pages its stages free stay in the
// process for its next stage (core/base/malloc_policy.h); once it ends they go back to the
// system, so that a server whose jobs and results are gone does not stay near its peak RSS.
// Chosen by measurement (tests/bench/2026-12-02-server-memory.txt,
// tests/bench/2026-12-05-server-malloc.txt, docs/memory-decisions.md).
#ifndef MEMBRANE_SERVER_MEMORY_RELEASE_H_
#define MEMBRANE_SERVER_MEMORY_RELEASE_H_

namespace membrane::server {

// Returns the free pages of the malloc heap to the system (malloc_trim(0)). Costs a walk of
// the heap's free lists (milliseconds after a large job); call it after a job or a batch of
// results is freed, not per call.
void ReleaseFreedMemory();

// Sets the process's malloc policy (one arena that keeps what it frees, KeepFreedBlocksInOneHeap)
// unless the operator chose malloc's settings in the environment: MALLOC_ARENA_MAX set, or
// GLIBC_TUNABLES naming a glibc.malloc tunable other than the huge pages' (kHugePageTunable).
// Those stand, on glibc's defaults otherwise.
// Returns whether the policy was set. Call before any thread starts.
bool UseMallocPolicyUnlessChosen();

}  // namespace membrane::server

#endif  // MEMBRANE_SERVER_MEMORY_RELEASE_H_
