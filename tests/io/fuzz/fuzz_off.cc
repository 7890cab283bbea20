// libFuzzer entry point for the OFF reader (clouds and meshes).
#include <cstddef>
#include <cstdint>

#include "tests/io/fuzz/fuzz_check.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  membrane::fuzzing::CheckReaders(data, size, membrane::FileFormat::kOff);
  return 0;
}
