// bench_crossing_search: the whole-mesh crossing search (FindIntersectingFaces,
// core/mesh/self_intersection.h) alone, on saved meshes (`membrane reconstruct ... -o mesh.ply`
// gives one), repeated in one process: the search's CPU without the pipeline around it. Per
// mesh: faces, the pairs found and a hash of them (two builds must print the same), and the
// median of the runs' process CPU and wall seconds with the CPU per face. Run by hand:
//   bench_crossing_search [--threads N] [--repeat R] MESH...
// Exit status 1 when a mesh cannot be read or two runs disagree on the pairs.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <string>
#include <utility>
#include <vector>

#include "absl/strings/numbers.h"
#include "absl/strings/string_view.h"
#include "core/io/mesh_io.h"
#include "core/mesh/self_intersection.h"
#include "tests/bench/bench_util.h"

namespace membrane::bench {
namespace {

// FNV-1a over the pairs in order: equal lists give equal hashes on any build.
uint64_t HashPairs(const std::vector<std::pair<int32_t, int32_t>>& pairs) {
  uint64_t h = 1469598103934665603ull;
  for (const auto& [a, b] : pairs)
    for (int32_t v : {a, b}) {
      h ^= static_cast<uint32_t>(v);
      h *= 1099511628211ull;
    }
  return h;
}

int Run(int argc, char** argv) {
  int threads = 1, repeat = 5;
  std::vector<std::string> paths;
  for (int i = 1; i < argc; ++i) {
    const absl::string_view arg = argv[i];
    const bool has_value = i + 1 < argc;
    if (arg == "--threads" && has_value && absl::SimpleAtoi(argv[i + 1], &threads) &&
        threads >= 1) {
      ++i;
    } else if (arg == "--repeat" && has_value && absl::SimpleAtoi(argv[i + 1], &repeat) &&
               repeat >= 1) {
      ++i;
    } else if (!arg.empty() && arg[0] != '-') {
      paths.emplace_back(arg);
    } else {
      std::fprintf(stderr, "usage: bench_crossing_search [--threads N] [--repeat R] MESH...\n");
      return 2;
    }
  }
  std::printf("threads %d, repeat %d, load %s\n", threads, repeat, LoadAverage().c_str());
  std::printf("%-40s %10s %8s %18s %9s %9s %9s\n", "mesh", "faces", "pairs", "hash", "cpu s",
              "wall s", "ns/face");
  for (const std::string& path : paths) {
    absl::StatusOr<TriangleMesh> mesh = ReadMesh(path);
    if (!mesh.ok()) {
      std::fprintf(stderr, "%s: %s\n", path.c_str(), mesh.status().ToString().c_str());
      return 1;
    }
    std::vector<double> cpu, wall;
    std::vector<std::pair<int32_t, int32_t>> first;
    for (int r = 0; r < repeat; ++r) {
      const double c0 = ClockSeconds(CLOCK_PROCESS_CPUTIME_ID), w0 = Now();
      std::vector<std::pair<int32_t, int32_t>> pairs =
          FindIntersectingFaces(*mesh, CancelToken::Never(), threads);
      cpu.push_back(ClockSeconds(CLOCK_PROCESS_CPUTIME_ID) - c0);
      wall.push_back(Now() - w0);
      if (r == 0) {
        first = std::move(pairs);
      } else if (pairs != first) {
        std::fprintf(stderr, "%s: run %d found other pairs than run 0\n", path.c_str(), r);
        return 1;
      }
    }
    const double faces = static_cast<double>(mesh->faces.size());
    std::printf("%-40s %10zu %8zu %018llx %9.4f %9.4f %9.1f\n", path.c_str(), mesh->faces.size(),
                first.size(), static_cast<unsigned long long>(HashPairs(first)), Median(cpu),
                Median(wall), 1e9 * Median(cpu) / faces);
  }
  return 0;
}

}  // namespace
}  // namespace membrane::bench

int main(int argc, char** argv) { return membrane::bench::Run(argc, argv); }
