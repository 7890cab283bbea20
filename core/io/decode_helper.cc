#include "core/io/decode_helper.h"

#include <cstdint>
#include <cstdio>
#include <new>

#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "core/io/draco_codec.h"

namespace membrane {
namespace {

int Reject(const std::string& message, int code = kDecodeHelperRejected) {
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

int RunDecodeHelper(const std::vector<std::string>& args) {
  int64_t max_points = 0;
  const bool accept_mesh = args.size() == 2 && args[1] == kAcceptMeshArgument;
  if ((args.size() != 1 && !accept_mesh) || !absl::SimpleAtoi(args[0], &max_points)) {
    return Reject(absl::StrCat("usage: membrane-decode MAX_POINTS [", kAcceptMeshArgument, "]"));
  }
  const std::string bytes = ReadAll(stdin);
  if (bytes.empty()) return Reject("the Draco data is empty");
  absl::StatusOr<DecodedDracoCloud> decoded = absl::InternalError("not decoded");
  // Draco allocates what crafted counts ask for; under the parent's RLIMIT_AS that ends in
  // bad_alloc, which deserves a line of its own rather than an abort.
  try {
    decoded = DecodeDracoPointCloud(
        bytes, accept_mesh ? DracoMeshPolicy::kAcceptMeshVertices : DracoMeshPolicy::kRejectMesh);
  } catch (const std::bad_alloc&) {
    return Reject("the Draco decoder asked for more memory than its limit: the data is corrupt");
  }
  if (!decoded.ok()) return Reject(std::string(decoded.status().message()));
  const std::vector<Point3f>& points = decoded->cloud.points;
  if (points.empty()) return Reject("the cloud has no points");
  if (static_cast<int64_t>(points.size()) > max_points) {
    return Reject(absl::StrCat("the cloud has ", points.size(), " points, over the limit of ",
                               max_points, " (--max-points)"),
                  kDecodeHelperOverLimit);
  }
  const uint64_t count = points.size();
  // x86-64 and aarch64 are little-endian; the parent reads the same layout.
  if (std::fwrite(&count, sizeof count, 1, stdout) != 1 ||
      std::fwrite(points.data(), sizeof(Point3f), points.size(), stdout) != points.size() ||
      std::fflush(stdout) != 0) {
    return Reject("cannot write the points");
  }
  return 0;
}

}  // namespace membrane
