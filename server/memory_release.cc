#include "server/memory_release.h"

#include <malloc.h>

#include <cstdlib>
#include <cstring>

#include "core/base/malloc_policy.h"

namespace membrane::server {

void ReleaseFreedMemory() { malloc_trim(0); }

bool UseMallocPolicyUnlessChosen() {
  const char* tunables = std::getenv("GLIBC_TUNABLES");
  if (std::getenv("MALLOC_ARENA_MAX") != nullptr ||
      (tunables != nullptr && std::strstr(tunables, "glibc.malloc.") != nullptr)) {
    return false;
  }
  KeepFreedBlocksInOneHeap();
  return true;
}

}  // namespace membrane::server
