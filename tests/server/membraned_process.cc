#include "tests/server/membraned_process.h"

#include <regex>

#include <gtest/gtest.h>

namespace membrane::testing {

MembranedProcess StartMembraned(const ScratchDir& dir, const std::string& name,
                                const std::vector<std::string>& flags) {
  std::vector<std::string> argv = {MEMBRANED_BINARY, "--listen=127.0.0.1:0", "--workers=1",
                                   "--queue=2", "--grace_seconds=1"};
  argv.insert(argv.end(), flags.begin(), flags.end());
  MembranedProcess server;
  server.log = dir.File(name + ".log");
  server.process = std::make_unique<Subprocess>(argv, dir.File(name + ".out"), server.log);
  const std::string log = WaitForText(server.log, "event=server_started", 10);
  std::smatch m;
  if (std::regex_search(log, m, std::regex(" port=(\\d+)"))) {
    server.address = "127.0.0.1:" + m[1].str();
  } else {
    ADD_FAILURE() << name << " did not start: " << log;
  }
  return server;
}

}  // namespace membrane::testing
