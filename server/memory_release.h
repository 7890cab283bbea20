// Giving freed memory back to the system: glibc's malloc keeps the pages of freed blocks in its
// arenas (one per thread, up to 8 per core) for reuse, so a server whose jobs and results are
// gone would stay near its peak RSS. Chosen by measurement against MALLOC_ARENA_MAX alone,
// jemalloc and tcmalloc (tests/bench/2026-12-02-server-memory.txt, docs/memory-decisions.md).
#ifndef MEMBRANE_SERVER_MEMORY_RELEASE_H_
#define MEMBRANE_SERVER_MEMORY_RELEASE_H_

namespace membrane::server {

// Returns the free pages of every malloc arena to the system (malloc_trim(0)). Costs a walk of
// the arenas' free lists (milliseconds after a large job); call it after a job or a batch of
// results is freed, not per call.
void ReleaseFreedMemory();

// Caps glibc's malloc at kMallocArenas arenas, unless MALLOC_ARENA_MAX is set in the
// environment (the operator's choice stands). Call before any thread starts.
inline constexpr int kMallocArenas = 2;
void LimitMallocArenas();

}  // namespace membrane::server

#endif  // MEMBRANE_SERVER_MEMORY_RELEASE_H_
