#include "tests/cli/reconstruct_stats.h"

#include <fstream>
#include <optional>
#include <sstream>

#include "gtest/gtest.h"
#include "tests/support/cli_runner.h"

namespace membrane::testing {

JsonValue ReconstructStats(const ScratchDir& dir, const std::string& cloud,
                           const std::string& mesh_name,
                           const std::vector<std::string>& extra_flags) {
  const std::string stats = dir.File("stats.json");
  std::vector<std::string> args = {"reconstruct", cloud,          "-o", dir.File(mesh_name),
                                   "--local",     "--stats-json", stats};
  args.insert(args.end(), extra_flags.begin(), extra_flags.end());
  const CliResult r = RunMembrane(args, dir.path());
  EXPECT_EQ(r.exit_code, 0) << r.err;
  std::ifstream in(stats);
  std::stringstream text;
  text << in.rdbuf();
  std::optional<JsonValue> json = ParseJson(text.str());
  EXPECT_TRUE(json.has_value()) << text.str();
  return json.value_or(JsonValue{});
}

}  // namespace membrane::testing
