#include "server/memory_release.h"

#include <malloc.h>

#include <cstdlib>
#include <string>

#include "core/base/malloc_policy.h"

namespace membrane::server {

void ReleaseFreedMemory() { malloc_trim(0); }

bool UseMallocPolicyUnlessChosen() {
  if (std::getenv("MALLOC_ARENA_MAX") != nullptr) return false;
  // The huge pages' tunable says nothing of arenas, mapping or trimming; the process may have
  // set it itself (RestartWithHugePageHeap).
  for (const std::string& name : TunableNames(std::getenv("GLIBC_TUNABLES"))) {
    if (name.rfind("glibc.malloc.", 0) == 0 && name != kHugePageTunable) return false;
  }
  KeepFreedBlocksInOneHeap();
  return true;
}

}  // namespace membrane::server
