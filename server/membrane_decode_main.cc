// membrane-decode: decodes one Draco point cloud from stdin and writes its points to stdout,
// for membraned, which runs it in a child process under resource limits (core/io/
// decode_subprocess.h). Usage: membrane-decode MAX_POINTS [--accept-mesh]; the protocol and
// exit statuses are RunDecodeHelper's (core/io/decode_helper.h).
#include <string>
#include <vector>

#include "core/io/decode_helper.h"

int main(int argc, char** argv) {
  return membrane::RunDecodeHelper(std::vector<std::string>(argv + 1, argv + argc));
}
