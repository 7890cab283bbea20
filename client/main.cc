// `membrane`: the command-line client (client/command_line.h), and the Draco decode helper it
// runs on itself.
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "client/command_line.h"
#include "client/exit_codes.h"
#include "client/input_files.h"
#include "core/base/malloc_policy.h"
#include "core/io/decode_helper.h"

int main(int argc, char** argv) {
  // The heap on huge pages (the process starts again once for it), and freed memory stays
  // with the process for the next stage.
  membrane::RestartWithHugePageHeap("/proc/self/exe", argv);
  membrane::KeepFreedBlocksInOneHeap();
  // Run by ReadInputCloud on itself to decode a Draco file under resource limits.
  if (argc >= 2 && std::string(argv[1]) == membrane::client::kDecodeHelperFlag) {
    return membrane::RunDecodeHelper(std::vector<std::string>(argv + 2, argv + argc));
  }
  // Nothing may escape as an exception: a crash is not one readable line.
  try {
    return membrane::client::RunCommandLine(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "membrane: internal error: %s\n", e.what());
  } catch (...) {
    std::fprintf(stderr, "membrane: internal error\n");
  }
  return membrane::client::kExitJobFailed;
}
