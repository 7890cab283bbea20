// Locating ../shared/data for tests that use the real scans; they skip when it is absent.
#ifndef MEMBRANE_TESTS_SUPPORT_SHARED_DATA_H_
#define MEMBRANE_TESTS_SUPPORT_SHARED_DATA_H_

#include <optional>
#include <string>

namespace membrane::testing {

// The directory ../shared/data (from MEMBRANE_SHARED_DIR, set by ctest), or nullopt when it
// does not exist.
std::optional<std::string> SharedDataDir();

}  // namespace membrane::testing

// Skips the current test, with a message naming the missing directory, when ../shared/data is
// absent; otherwise defines `const std::string data_dir`.
#define MEMBRANE_REQUIRE_SHARED_DATA(data_dir)                                            \
  const auto data_dir##_opt = ::membrane::testing::SharedDataDir();                      \
  if (!data_dir##_opt) GTEST_SKIP() << "../shared/data is absent (set MEMBRANE_SHARED_DIR)"; \
  const std::string data_dir = *data_dir##_opt

#endif  // MEMBRANE_TESTS_SUPPORT_SHARED_DATA_H_
