// How a membrane process asks glibc's malloc to manage its memory. Each stage of a
// reconstruction allocates grid-sized arrays and frees them before the next stage allocates
// its own, so the pages one stage frees are the cheapest memory for the next
// (docs/memory-decisions.md, "A process keeps what it frees during a run"). The core never
// calls this: the executables do, once, at the start of main.
#ifndef MEMBRANE_CORE_BASE_MALLOC_POLICY_H_
#define MEMBRANE_CORE_BASE_MALLOC_POLICY_H_

namespace membrane {

// Whether the process runs glibc's malloc, which the policy sets: the sanitizers bring their
// own allocator, and the policy then changes nothing.
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
inline constexpr bool kGlibcMalloc = false;
#else
inline constexpr bool kGlibcMalloc = true;
#endif

// One arena for the process, no block mapped on its own, no automatic trim: every freed block
// stays in the one heap for the next allocation, until the process exits or calls
// malloc_trim. Must be called before the process starts a thread or makes its first large
// allocation.
void KeepFreedBlocksInOneHeap();

}  // namespace membrane

#endif  // MEMBRANE_CORE_BASE_MALLOC_POLICY_H_
