// What every io fuzz target asserts: readers return a status or well-formed geometry, for
// any bytes.
#ifndef MEMBRANE_TESTS_IO_FUZZ_FUZZ_CHECK_H_
#define MEMBRANE_TESTS_IO_FUZZ_FUZZ_CHECK_H_

#include <cstddef>
#include <cstdint>

#include "core/io/file_format.h"

// The entry point each fuzz target defines (fuzz_<format>.cc), called with every input by
// libFuzzer, or by replay_main.cc in a build without clang.
extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);

namespace membrane::fuzzing {

// Feeds `data` to ReadPointCloudFromBuffer as `format` (and, for formats that hold meshes,
// to ReadMeshFromBuffer) and aborts when a result is OK but holds a non-finite coordinate, an
// origin CoordinateShift would not give, or a face index outside the vertices. Crashes, leaks and sanitizer reports are the fuzzer's
// to catch.
void CheckReaders(const uint8_t* data, size_t size, FileFormat format);

}  // namespace membrane::fuzzing

#endif  // MEMBRANE_TESTS_IO_FUZZ_FUZZ_CHECK_H_
