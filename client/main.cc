// `membrane`: the command-line client (client/command_line.h), and the Draco decode helper it
// runs on itself.
#include <malloc.h>

#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "client/command_line.h"
#include "client/exit_codes.h"
#include "client/input_files.h"
#include "core/io/decode_helper.h"

int main(int argc, char** argv) {
  // One malloc arena for the process. `reconstruct --local` checks the mesh on a second thread
  // while it encodes; with an arena of its own that thread would fault in fresh pages instead
  // of reusing what the earlier stages freed (on rocker-arm-scan the check takes 0.23 s with
  // one arena and 0.36 s with glibc's default, the whole run 1.05 s and 1.27 s). Two threads
  // hardly contend for one arena.
  // The server keeps glibc's default: its workers allocate in parallel.
  mallopt(M_ARENA_MAX, 1);
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
