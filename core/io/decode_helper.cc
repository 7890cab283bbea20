#include "core/io/decode_helper.h"

#include <cstdint>
#include <cstdio>
#include <new>
#include <utility>
#include <vector>

#include "absl/strings/match.h"
#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_split.h"
#include "core/io/draco_codec.h"
#include "core/io/draco_parts.h"

namespace membrane {
namespace {

int Reject(const std::string& message, int code = kDecodeHelperRejected) {
  std::fprintf(stderr, "%s\n", message.c_str());
  return code;
}

// A count as a uint64, then the records of `pieces` one piece after the other, on stdout:
// a cloud's parts go out as they were decoded, without one array of all their points.
template <typename T>
bool WriteRecords(const std::vector<std::vector<T>>& pieces) {
  uint64_t count = 0;
  for (const std::vector<T>& piece : pieces) count += piece.size();
  if (std::fwrite(&count, sizeof count, 1, stdout) != 1) return false;
  for (const std::vector<T>& piece : pieces) {
    if (std::fwrite(piece.data(), sizeof(T), piece.size(), stdout) != piece.size()) return false;
  }
  return true;
}

std::string ReadAll(std::FILE* in) {
  std::string bytes;
  char buffer[1 << 16];
  size_t n;
  while ((n = std::fread(buffer, 1, sizeof buffer, in)) > 0) bytes.append(buffer, n);
  return bytes;
}

// The helper's arguments after MAX_POINTS.
struct HelperArguments {
  std::string mode;  // empty, kAcceptMeshArgument or kMeshArgument
  std::vector<uint64_t> part_bytes;
  int threads = 1;
};

bool ParseArguments(const std::vector<std::string>& args, HelperArguments& parsed) {
  for (size_t i = 1; i < args.size(); ++i) {
    absl::string_view arg = args[i];
    if ((arg == kAcceptMeshArgument || arg == kMeshArgument) && parsed.mode.empty()) {
      parsed.mode = args[i];
    } else if (absl::ConsumePrefix(&arg, kPartsArgument) && parsed.part_bytes.empty()) {
      for (absl::string_view size : absl::StrSplit(arg, ',')) {
        if (!absl::SimpleAtoi(size, &parsed.part_bytes.emplace_back())) return false;
      }
    } else if (absl::ConsumePrefix(&arg, kThreadsArgument)) {
      if (!absl::SimpleAtoi(arg, &parsed.threads) || parsed.threads < 1) return false;
    } else {
      return false;
    }
  }
  return parsed.mode != kMeshArgument || parsed.part_bytes.empty();
}

}  // namespace

int RunDecodeHelper(const std::vector<std::string>& args) {
  int64_t max_points = 0;
  HelperArguments parsed;
  if (args.empty() || !absl::SimpleAtoi(args[0], &max_points) || !ParseArguments(args, parsed)) {
    return Reject(absl::StrCat("usage: membrane-decode MAX_POINTS [", kAcceptMeshArgument, " | ",
                               kMeshArgument, "] [", kPartsArgument, "BYTES,BYTES,...] [",
                               kThreadsArgument, "N]"));
  }
  const std::string& mode = parsed.mode;
  const std::string bytes = ReadAll(stdin);
  if (bytes.empty()) return Reject("the Draco data is empty");
  // A mesh's vertices, or a cloud's points part after part (one piece for one part).
  std::vector<std::vector<Point3f>> points;
  std::vector<decltype(TriangleMesh::faces)> faces(1);
  // Draco allocates what crafted counts ask for; under the parent's RLIMIT_AS that ends in
  // bad_alloc, which deserves a line of its own rather than an abort.
  try {
    if (mode == kMeshArgument) {
      absl::StatusOr<TriangleMesh> decoded = DecodeDracoMesh(bytes);
      if (!decoded.ok()) return Reject(std::string(decoded.status().message()));
      points.push_back(std::move(decoded->vertices));
      faces.front() = std::move(decoded->faces);
    } else {
      absl::StatusOr<std::vector<DecodedDracoCloud>> decoded = DecodeDracoParts(
          bytes, parsed.part_bytes,
          mode == kAcceptMeshArgument ? DracoMeshPolicy::kAcceptMeshVertices
                                      : DracoMeshPolicy::kRejectMesh,
          parsed.threads);
      if (!decoded.ok()) return Reject(std::string(decoded.status().message()));
      for (DecodedDracoCloud& part : *decoded) points.push_back(std::move(part.cloud.points));
    }
  } catch (const std::bad_alloc&) {
    return Reject("the Draco decoder asked for more memory than its limit: the data is corrupt");
  }
  size_t count = 0;
  for (const std::vector<Point3f>& piece : points) count += piece.size();
  if (count == 0 && mode != kMeshArgument) return Reject("the cloud has no points");
  if (static_cast<int64_t>(count) > max_points) {
    return Reject(absl::StrCat("the ", mode == kMeshArgument ? "mesh" : "cloud", " has ", count,
                               " points, over the limit of ", max_points, " (--max-points)"),
                  kDecodeHelperOverLimit);
  }
  // x86-64 and aarch64 are little-endian; the parent reads the same layout.
  const bool written = WriteRecords(points) && (mode != kMeshArgument || WriteRecords(faces));
  if (!written || std::fflush(stdout) != 0) return Reject("cannot write the result");
  return 0;
}

}  // namespace membrane
