// membrane-decode: decodes one Draco point cloud from stdin and writes its points to stdout,
// for membraned, which runs it in a child process under resource limits (see
// server/decode_subprocess.h). Usage: membrane-decode MAX_POINTS
// Output on success (exit 0): the point count as a little-endian uint64, then x y z float32
// per point. On rejection: one line on stderr naming the problem, exit 3 for bytes that are
// not an acceptable cloud, 4 for a cloud over MAX_POINTS.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "core/io/draco_codec.h"

namespace {

constexpr int kExitRejected = 3;
constexpr int kExitOverLimit = 4;

int Reject(const std::string& message, int code = kExitRejected) {
  std::fprintf(stderr, "%s\n", message.c_str());
  return code;
}

std::string ReadAll(std::FILE* in) {
  std::string bytes;
  char buffer[1 << 16];
  size_t n;
  while ((n = std::fread(buffer, 1, sizeof buffer, in)) > 0) bytes.append(buffer, n);
  return bytes;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) return Reject("usage: membrane-decode MAX_POINTS");
  const long long max_points = std::atoll(argv[1]);
  const std::string bytes = ReadAll(stdin);
  if (bytes.empty()) return Reject("the upload is empty");
  absl::StatusOr<membrane::DecodedDracoCloud> decoded =
      membrane::DecodeDracoPointCloud(bytes, membrane::DracoMeshPolicy::kRejectMesh);
  if (!decoded.ok()) return Reject(std::string(decoded.status().message()));
  const std::vector<membrane::Point3f>& points = decoded->cloud.points;
  if (points.empty()) return Reject("the cloud has no points");
  if (static_cast<long long>(points.size()) > max_points) {
    return Reject("the cloud has " + std::to_string(points.size()) +
                  " points, over the server's limit of " + std::to_string(max_points) +
                  " (--max-points)",
                  kExitOverLimit);
  }
  const uint64_t count = points.size();
  // x86-64 and aarch64 are little-endian; the parent reads the same layout.
  if (std::fwrite(&count, sizeof count, 1, stdout) != 1 ||
      std::fwrite(points.data(), sizeof(membrane::Point3f), points.size(), stdout) !=
          points.size() ||
      std::fflush(stdout) != 0) {
    return Reject("cannot write the points");
  }
  return 0;
}
