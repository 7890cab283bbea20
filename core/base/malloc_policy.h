// How a membrane process asks glibc's malloc to manage its memory. Each stage of a
// reconstruction allocates grid-sized arrays and frees them before the next stage allocates
// its own, so the pages one stage frees are the cheapest memory for the next
// (docs/memory-decisions.md, "A process keeps what it frees during a run"), and the arrays are
// read at random across gigabytes, where pages of 2 MB spare the address translation ("The
// heap on transparent huge pages"). The core never calls this: the executables do, once, at
// the start of main.
#ifndef MEMBRANE_CORE_BASE_MALLOC_POLICY_H_
#define MEMBRANE_CORE_BASE_MALLOC_POLICY_H_

#include <optional>
#include <string>
#include <vector>

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

// The names of the tunables in a GLIBC_TUNABLES value (name=value pairs separated by colons;
// null: the variable is unset), in order.
std::vector<std::string> TunableNames(const char* tunables);

// The tunable that makes glibc's malloc advise MADV_HUGEPAGE on the memory it takes.
inline constexpr char kHugePageTunable[] = "glibc.malloc.hugetlb";

// The GLIBC_TUNABLES value that asks glibc's malloc to advise transparent huge pages for the
// memory it takes from the system (glibc.malloc.hugetlb=1), appended to `current` (null when
// the variable is unset); nullopt when `current` already names glibc.malloc.hugetlb: the
// operator's choice, or a process started again for it, stands.
std::optional<std::string> TunablesWithHugePageHeap(const char* current);

// Whether the kernel gives transparent huge pages only to memory advised MADV_HUGEPAGE
// (/sys/kernel/mm/transparent_hugepage/enabled reads "[madvise]"): under "always" the heap has
// them without advice, under "never" (or without the file) it gets none with it.
bool KernelGivesHugePagesOnlyWhenAdvised();

// When glibc's malloc runs, KernelGivesHugePagesOnlyWhenAdvised() and GLIBC_TUNABLES does not
// name glibc.malloc.hugetlb: replaces the process with `executable` run on `argv` (null
// terminated) and the same environment but for TunablesWithHugePageHeap's GLIBC_TUNABLES
// (glibc reads its tunables only when a process starts). Returns otherwise, and when the exec
// fails, with the environment as it was: the process then goes on with plain pages. Call it
// first in main, before any thread starts, with "/proc/self/exe" and main's argv.
void RestartWithHugePageHeap(const char* executable, char** argv);

}  // namespace membrane

#endif  // MEMBRANE_CORE_BASE_MALLOC_POLICY_H_
