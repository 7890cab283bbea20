// bench_decimate: DecimateMesh (core/mesh/mesh_decimation.h) on one core, in faces removed per
// second, with the error it adds (MeasureDeviation: the distance from the vertices before to
// the surface after, as % of the bounding-box diagonal) and the check of the result (closed,
// manifold, oriented, crossings, shells and genus as before). Meshes:
//   - torus-N: a regular torus mesh of about N faces (the 15M-face one is the size a
//     10M-point scan's surface has), decimated to 1/15 and to 1/100 of its faces;
//   - the smooth surface of every real cloud of ../shared/data on the 11-bit grid of a .drc
//     output (RunReconstruction's own surface), decimated to 10% and 1%.
// Exit status 1 when a result breaks a promise. See README.md.
#include <sys/resource.h>
#include <time.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_join.h"
#include "core/io/point_cloud_io.h"
#include "core/mesh/mesh_check.h"
#include "core/mesh/mesh_decimation.h"
#include "core/mesh/surface_deviation.h"
#include "core/pipeline/in_memory_ends.h"
#include "core/pipeline/reconstruction_pipeline.h"
#include "tests/bench/bench_util.h"

namespace membrane::bench {
namespace {

namespace fs = std::filesystem;

struct BenchOptions {
  bool quick = false;
  bool torus = true, real = true;
  int torus_side = 0;  // > 0: only the torus of this many rings and segments
  std::string shared_dir;
};

// A torus around z of `rings` x `segments` quads split in two, outward: 2 rings segments faces.
TriangleMesh Torus(int rings, int segments) {
  constexpr double kMajor = 1.0, kMinor = 0.4, kTwoPi = 6.283185307179586;
  TriangleMesh mesh;
  mesh.vertices.reserve(static_cast<size_t>(rings) * segments);
  for (int i = 0; i < rings; ++i)
    for (int j = 0; j < segments; ++j) {
      const double u = kTwoPi * i / rings, v = kTwoPi * j / segments;
      const double r = kMajor + kMinor * std::cos(v);
      mesh.vertices.push_back({static_cast<float>(r * std::cos(u)),
                               static_cast<float>(r * std::sin(u)),
                               static_cast<float>(kMinor * std::sin(v))});
    }
  mesh.faces.reserve(2 * static_cast<size_t>(rings) * segments);
  auto at = [&](int i, int j) { return ((i % rings) * segments) + (j % segments); };
  for (int i = 0; i < rings; ++i)
    for (int j = 0; j < segments; ++j) {
      const int32_t a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1), d = at(i, j + 1);
      mesh.faces.push_back({a, b, c});
      mesh.faces.push_back({a, c, d});
    }
  return mesh;
}

double Diagonal(const TriangleMesh& mesh) {
  std::array<float, 3> lo = mesh.vertices[0], hi = mesh.vertices[0];
  for (const Point3f& p : mesh.vertices)
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], p[k]);
      hi[k] = std::max(hi[k], p[k]);
    }
  return std::hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]);
}

double PeakRssMb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss / 1024.0;
}

// One decimation, one line. False when the result breaks a promise.
bool Run(const std::string& name, const TriangleMesh& mesh, const PositionGrid& grid,
         int64_t target) {
  const MeshReport before = CheckMesh(mesh, CancelToken::Never(), 2);
  TriangleMesh decimated = mesh;
  const double start = Now(), cpu_start = ClockSeconds(CLOCK_THREAD_CPUTIME_ID);
  absl::StatusOr<DecimationStats> stats =
      DecimateMesh(decimated, {.target_faces = target, .grid = grid});
  const double seconds = Now() - start, cpu = ClockSeconds(CLOCK_THREAD_CPUTIME_ID) - cpu_start;
  if (!stats.ok()) {
    std::printf("%-28s FAILED: %s\n", name.c_str(), std::string(stats.status().message()).c_str());
    return false;
  }
  const double error_start = Now();
  const SurfaceDeviation error = MeasureDeviation(mesh.vertices, decimated, 1);
  const double error_seconds = Now() - error_start;
  const MeshReport r = CheckMesh(decimated, CancelToken::Never(), 2);
  std::vector<int> g0 = before.genus, g1 = r.genus;
  std::sort(g0.begin(), g0.end());
  std::sort(g1.begin(), g1.end());
  const bool ok = r.closed && r.manifold && r.oriented && r.positive_volume &&
                  r.degenerate_faces == 0 && r.self_intersections <= before.self_intersections &&
                  r.shells == before.shells && g0 == g1;
  const double diagonal = Diagonal(mesh);
  std::printf(
      "%-24s %9lld -> %8lld (target %8lld) %7.2f s wall %7.2f s cpu %9.0f faces/s cpu  "
      "error max %.4f%% mean %.5f%% (%.2f s)  %s g[%s]  rss %.0f MB\n",
      name.c_str(), static_cast<long long>(stats->faces_before),
      static_cast<long long>(stats->faces_after), static_cast<long long>(target), seconds, cpu,
      (stats->faces_before - stats->faces_after) / cpu, 100 * error.max / diagonal,
      100 * error.mean / diagonal, error_seconds, ok ? "ok" : "BROKEN",
      absl::StrJoin(r.genus, ",").c_str(), PeakRssMb());
  std::fflush(stdout);
  return ok;
}

bool RunTori(const BenchOptions& o) {
  bool ok = true;
  // rings x segments with 2 r s faces: 150k, 1.5M, 15M.
  std::vector<std::pair<int, int>> sizes = {{274, 274}, {866, 866}};
  if (!o.quick) sizes.push_back({2740, 2740});
  if (o.quick) sizes = {{100, 100}};
  if (o.torus_side > 0) sizes = {{o.torus_side, o.torus_side}};
  for (auto [rings, segments] : sizes) {
    const TriangleMesh torus = Torus(rings, segments);
    const int64_t faces = static_cast<int64_t>(torus.faces.size());
    const std::string name = absl::StrCat("torus-", faces);
    ok &= Run(name + " /15", torus, PositionGrid{}, faces / 15);
    ok &= Run(name + " /100", torus, PositionGrid{}, faces / 100);
  }
  return ok;
}

bool RunRealClouds(const BenchOptions& o) {
  const fs::path dir = fs::path(o.shared_dir) / "data" / "clouds";
  if (!fs::is_directory(dir)) {
    std::printf("real clouds: skipped, %s is absent\n", dir.c_str());
    return true;
  }
  std::vector<fs::path> clouds;
  for (const auto& entry : fs::directory_iterator(dir))
    if (entry.path().extension() == ".ply") clouds.push_back(entry.path());
  std::sort(clouds.begin(), clouds.end());
  if (o.quick && clouds.size() > 1) clouds.resize(1);
  bool ok = true;
  for (const fs::path& path : clouds) {
    absl::StatusOr<PointCloud> cloud = ReadPointCloud(path.string());
    if (!cloud.ok()) {
      std::printf("%s: %s\n", path.c_str(), std::string(cloud.status().message()).c_str());
      ok = false;
      continue;
    }
    // The surface as `membrane reconstruct` delivers it in a .drc file.
    InMemoryCloudSource source(*cloud);
    NoResourceLimit gate;
    InMemoryMeshSink sink;
    NullReconstructionObserver observer;
    ReconstructionOptions options;
    options.output_quantization_bits = 11;
    absl::StatusOr<ReconstructionReport> report = RunReconstruction(
        options, {source, gate, sink, observer}, ErrorContext{}, CancelToken::Never());
    if (!report.ok()) {
      std::printf("%s: %s\n", path.c_str(), std::string(report.status().message()).c_str());
      ok = false;
      continue;
    }
    const int64_t faces = static_cast<int64_t>(sink.mesh().faces.size());
    const std::string name = path.stem().string();
    ok &= Run(name + " 10%", sink.mesh(), sink.grid(), faces / 10);
    ok &= Run(name + " 1%", sink.mesh(), sink.grid(), faces / 100);
  }
  return ok;
}

}  // namespace
}  // namespace membrane::bench

int main(int argc, char** argv) {
  using namespace membrane::bench;
  BenchOptions o;
  const char* env = std::getenv("MEMBRANE_SHARED_DIR");
  o.shared_dir = env != nullptr && *env != '\0' ? env : MEMBRANE_SOURCE_DIR "/../shared";
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--quick") {
      o.quick = true;
    } else if (arg == "--torus-only") {
      o.real = false;
    } else if (arg == "--real-only") {
      o.torus = false;
    } else if (arg == "--torus-side" && i + 1 < argc) {
      o.torus_side = std::atoi(argv[++i]);
      o.real = false;
    } else if (arg == "--shared" && i + 1 < argc) {
      o.shared_dir = argv[++i];
    } else {
      std::fprintf(stderr,
                   "usage: bench_decimate [--quick] [--torus-only | --real-only | --torus-side N] "
                   "[--shared DIR]\n");
      return 2;
    }
  }
  std::printf("# bench_decimate%s: one core; load %s\n", o.quick ? " --quick" : "",
              LoadAverage().c_str());
  bool ok = true;
  if (o.torus) ok &= RunTori(o);
  if (o.real) ok &= RunRealClouds(o);
  return ok ? 0 : 1;
}
