// membraned started as a process for end-to-end tests, on a free loopback port.
#ifndef MEMBRANE_TESTS_SERVER_MEMBRANED_PROCESS_H_
#define MEMBRANE_TESTS_SERVER_MEMBRANED_PROCESS_H_

#include <memory>
#include <string>
#include <vector>

#include "tests/server/subprocess.h"
#include "tests/support/scratch_dir.h"

namespace membrane::testing {

struct MembranedProcess {
  std::unique_ptr<Subprocess> process;
  std::string address;  // 127.0.0.1:PORT; empty when it did not start (the test has failed)
  std::string log;      // its stderr: the structured log lines
};

// Starts MEMBRANED_BINARY on 127.0.0.1:0 with 1 worker, a queue of 2 and 1 s of grace, then
// `flags` (which may override them), logging to `dir`/`name`.log, and waits up to 10 s for its
// port. A test failure when it does not start.
MembranedProcess StartMembraned(const ScratchDir& dir, const std::string& name,
                                const std::vector<std::string>& flags = {});

}  // namespace membrane::testing

#endif  // MEMBRANE_TESTS_SERVER_MEMBRANED_PROCESS_H_
