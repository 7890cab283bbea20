#include "tests/support/shared_data.h"

#include <cstdlib>
#include <filesystem>

namespace membrane::testing {

std::optional<std::string> SharedDataDir() {
  const char* env = std::getenv("MEMBRANE_SHARED_DIR");
  std::filesystem::path dir = env != nullptr ? env : "../shared";
  dir /= "data";
  std::error_code ec;
  if (!std::filesystem::is_directory(dir, ec)) return std::nullopt;
  return dir.string();
}

}  // namespace membrane::testing
