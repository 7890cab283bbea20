// For tests of what a process does once the kernel refuses it another mapping.
#ifndef MEMBRANE_TESTS_SERVER_EVERY_MAPPING_H_
#define MEMBRANE_TESTS_SERVER_EVERY_MAPPING_H_

#include <sys/mman.h>

namespace membrane::server {

// Maps pages one by one until the kernel refuses (vm.max_map_count reached), never unmapping
// them: call it in a child process. False when a million mappings were not refused.
inline bool TakeEveryMappingLeft() {
  for (int i = 0; i < 1 << 20; ++i) {
    // Alternate protections so that neighbouring mappings do not merge into one.
    if (mmap(nullptr, 4096, i % 2 == 0 ? PROT_READ : PROT_NONE, MAP_PRIVATE | MAP_ANONYMOUS, -1,
             0) == MAP_FAILED) {
      return true;
    }
  }
  return false;
}

}  // namespace membrane::server

#endif  // MEMBRANE_TESTS_SERVER_EVERY_MAPPING_H_
