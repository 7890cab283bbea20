// Locating ../shared/data for tests that use the real scans; they skip when it is absent.
#ifndef MEMBRANE_TESTS_SUPPORT_SHARED_DATA_H_
#define MEMBRANE_TESTS_SUPPORT_SHARED_DATA_H_

#include <optional>
#include <string>

#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "core/geometry/point_cloud.h"

namespace membrane::testing {

// The directory ../shared/data (from MEMBRANE_SHARED_DIR, set by ctest), or nullopt when it
// does not exist.
std::optional<std::string> SharedDataDir();

// The cloud `name` of `data_dir` (SharedDataDir()'s), read from data_dir/clouds/name.ply;
// ReadPointCloud's errors.
absl::StatusOr<PointCloud> ReadSharedCloud(absl::string_view data_dir, absl::string_view name);

}  // namespace membrane::testing

// Skips the current test, with a message naming the missing directory, when ../shared/data is
// absent; otherwise defines `const std::string data_dir`.
#define MEMBRANE_REQUIRE_SHARED_DATA(data_dir)                                            \
  const auto data_dir##_opt = ::membrane::testing::SharedDataDir();                      \
  if (!data_dir##_opt) GTEST_SKIP() << "../shared/data is absent (set MEMBRANE_SHARED_DIR)"; \
  const std::string data_dir = *data_dir##_opt

#endif  // MEMBRANE_TESTS_SUPPORT_SHARED_DATA_H_
