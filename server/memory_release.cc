#include "server/memory_release.h"

#include <malloc.h>

#include <cstdlib>

namespace membrane::server {

void ReleaseFreedMemory() { malloc_trim(0); }

void LimitMallocArenas() {
  if (std::getenv("MALLOC_ARENA_MAX") == nullptr) mallopt(M_ARENA_MAX, kMallocArenas);
}

}  // namespace membrane::server
