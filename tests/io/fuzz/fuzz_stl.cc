// libFuzzer entry point for the STL reader (meshes for `membrane check` and `convert`).
#include <cstddef>
#include <cstdint>

#include "tests/io/fuzz/fuzz_check.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  membrane::fuzzing::CheckReaders(data, size, membrane::FileFormat::kStl);
  return 0;
}
