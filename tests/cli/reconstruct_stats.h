// Runs `membrane reconstruct --local --stats-json` and reads back the statistics it wrote.
#ifndef MEMBRANE_TESTS_CLI_RECONSTRUCT_STATS_H_
#define MEMBRANE_TESTS_CLI_RECONSTRUCT_STATS_H_

#include <string>
#include <vector>

#include "tests/cli/json_value.h"
#include "tests/support/scratch_dir.h"

namespace membrane::testing {

// Reconstructs `cloud` into `dir`/`mesh_name` with --local --stats-json and `extra_flags`, and
// returns the parsed statistics. A non-zero exit or unreadable JSON fails the calling test
// (non-fatally) and gives an empty value.
JsonValue ReconstructStats(const ScratchDir& dir, const std::string& cloud,
                           const std::string& mesh_name,
                           const std::vector<std::string>& extra_flags = {});

}  // namespace membrane::testing

#endif  // MEMBRANE_TESTS_CLI_RECONSTRUCT_STATS_H_
