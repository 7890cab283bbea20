// Run by malloc_policy_test through RestartWithHugePageHeap: whether a process started with
// the huge pages' tunable keeps a block of its one heap on huge pages, and gives it back to the
// system when trimmed (as membraned does after a job). Exits 0 when a written 64 MB block lies
// on them and malloc_trim then returns them, 5 when GLIBC_TUNABLES does not name the tunable,
// 6 when the heap has no huge page, 7 when the trim keeps the block's memory, 3 when the block
// cannot be allocated.
#include <malloc.h>

#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>

#include "core/base/malloc_policy.h"

namespace {

// The kB of this process's memory on the line `key` of /proc/self/smaps_rollup, or -1.
long RollupKb(const std::string& key) {
  std::ifstream file("/proc/self/smaps_rollup");
  for (std::string line; std::getline(file, line);) {
    if (line.compare(0, key.size(), key) == 0) return std::atol(line.c_str() + key.size());
  }
  return -1;
}

}  // namespace

int main() {
  if (membrane::TunablesWithHugePageHeap(std::getenv("GLIBC_TUNABLES"))) return 5;
  membrane::KeepFreedBlocksInOneHeap();
  constexpr size_t kBytes = size_t{64} << 20;
  char* block = static_cast<char*>(std::malloc(kBytes));
  if (block == nullptr) return 3;
  std::memset(block, 1, kBytes);
  // The block escapes: without it the compiler may drop the allocation and its writes.
  asm volatile("" : : "r"(block) : "memory");
  const long huge = RollupKb("AnonHugePages:");
  const long rss = RollupKb("Rss:");
  std::free(block);
  if (huge <= 0) return 6;
  malloc_trim(0);
  // At least 48 MB of the 64 back to the system.
  return RollupKb("Rss:") < rss - 48 * 1024 ? 0 : 7;
}
