#include "tests/support/shared_data.h"

#include <cstdlib>
#include <filesystem>

#include "absl/strings/str_cat.h"
#include "core/io/point_cloud_io.h"

namespace membrane::testing {

std::optional<std::string> SharedDataDir() {
  const char* env = std::getenv("MEMBRANE_SHARED_DIR");
  std::filesystem::path dir = env != nullptr ? env : "../shared";
  dir /= "data";
  std::error_code ec;
  if (!std::filesystem::is_directory(dir, ec)) return std::nullopt;
  return dir.string();
}

absl::StatusOr<PointCloud> ReadSharedCloud(absl::string_view data_dir, absl::string_view name) {
  return ReadPointCloud(absl::StrCat(data_dir, "/clouds/", name, ".ply"));
}

}  // namespace membrane::testing
