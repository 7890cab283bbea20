// bench_scale: how each stage's cost grows with the cloud. One synthetic shape (default the
// torus of `membrane synth torus`) at several point counts, each a whole RunReconstruction to
// an in-memory Draco file, formula-(1) voxel. Per stage: wall and CPU seconds, CPU microseconds
// per input point and per output face, and the ratio of the stage's figure (per point up to
// the shrink, per face after) to the first (smallest) count's; then each count's peak RSS.
// The output bits are those `membrane reconstruct` and membraned choose when none are asked:
// the fewest from 11 whose step is within kMaxOutputStepVoxels (13 at 100k points, 16 at
// 10M). `--bits` fixes them: on a grid too wide for them the fit's snapped
// vertices cross by the thousands and the surface's cost per face grows with the repairs, not
// with the cloud. CPU time, because these machines are shared: a loaded machine stretches the
// wall time, not the CPU time. The check runs beside the encode, so its CPU time holds the
// encode's too. Each count runs in a child process of its own, so that its peak RSS is its
// own. See README.md.
//
// Exit status 1 when a run fails.
#include <sys/resource.h>

#include <time.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "absl/strings/numbers.h"
#include "absl/strings/str_split.h"
#include "core/base/malloc_policy.h"
#include "core/pipeline/draco_mesh_sink.h"
#include "core/pipeline/in_memory_ends.h"
#include "core/pipeline/pipeline_stage.h"
#include "core/pipeline/reconstruction_pipeline.h"
#include "core/synth/synthesize.h"
#include "tests/bench/bench_util.h"
#include "tests/bench/child_process.h"

namespace membrane::bench {
namespace {

constexpr char kUsage[] =
    "usage: bench_scale [--points N,N,...] [--shape NAME] [--threads N] [--bits B] [--quick]\n"
    "  --points LIST  point counts, smallest first (default 100000,1000000)\n"
    "  --shape NAME   a shape of `membrane synth` (default torus)\n"
    "  --threads N    ReconstructionOptions::threads, 1..256 (default 1)\n"
    "  --bits B       output quantization bits, 0..30 (default 11, the .drc default)\n"
    "  --quick        20000 and 60000 points (the ctest smoke)\n";

struct Options {
  std::vector<int64_t> points = {100'000, 1'000'000};
  std::string shape = "torus";
  int threads = 1;
  int bits = 11;
  bool bits_follow_voxel = true;  // false once --bits is given
};

constexpr int kStages = static_cast<int>(PipelineStage::kEncode) + 1;

// What one count's child reports back through its pipe.
struct Row {
  int64_t points = 0, faces = 0, voxels = 0;
  double voxel_size = 0;
  int grid[3] = {0, 0, 0};
  int bits = 0;  // the bits the file got: 0 when the run fell back to float32
  double seconds[kStages] = {};      // wall, by PipelineStage
  double cpu_seconds[kStages] = {};  // the process's, same stages
  double total = 0, cpu = 0;
  int64_t peak_rss = 0;
  bool ok = false;
};


bool ParseArgs(int argc, char** argv, Options& o) {
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const bool has_value = i + 1 < argc;
    if (a == "--quick") {
      o.points = {20'000, 60'000};
    } else if (a == "--points" && has_value) {
      if (!ParsePointCounts(argv[++i], o.points)) return false;
    } else if (a == "--shape" && has_value) {
      o.shape = argv[++i];
    } else if (a == "--threads" && has_value) {
      if (!absl::SimpleAtoi(argv[++i], &o.threads) || o.threads < 1 || o.threads > 256)
        return false;
    } else if (a == "--bits" && has_value) {
      if (!absl::SimpleAtoi(argv[++i], &o.bits) || o.bits < 0 || o.bits > 30) return false;
      o.bits_follow_voxel = false;
    } else {
      return false;
    }
  }
  return true;
}

// The process's CPU seconds per stage; a stage run twice (the float32 retry) counts both.
class CpuObserver : public ReconstructionObserver {
 public:
  void StageStarted(PipelineStage, const ReconstructionReport&) override {
    start_ = ClockSeconds(CLOCK_PROCESS_CPUTIME_ID);
  }
  void GenerationFinished(const GenerationStats&, int) override {}
  void StageFinished(PipelineStage stage, double, const ReconstructionReport&) override {
    seconds[static_cast<int>(stage)] += ClockSeconds(CLOCK_PROCESS_CPUTIME_ID) - start_;
  }
  double seconds[kStages] = {};

 private:
  double start_ = 0;
};

// In the child: synthesizes the cloud and reconstructs it.
Row RunOne(const Options& o, int64_t points) {
  Row row;
  row.points = points;
  SynthOptions synth;
  synth.shape = o.shape;
  synth.points = points;
  absl::StatusOr<PointCloud> cloud = SynthesizeShape(synth);
  if (!cloud.ok()) {
    std::fprintf(stderr, "synth %s %lld: %s\n", o.shape.c_str(), static_cast<long long>(points),
                 cloud.status().ToString().c_str());
    return row;
  }
  ReconstructionOptions options;
  options.output_quantization_bits = o.bits;
  options.output_bits_follow_voxel = o.bits_follow_voxel;
  options.threads = o.threads;
  // The budget a dense grid of this count needs: the bench measures cost, not admission.
  options.voxelize.voxel_budget = int64_t{1} << 40;
  InMemoryCloudSource source(*std::move(cloud));
  NoResourceLimit gate;
  DracoMeshSink sink(/*compression_level=*/7);  // the .drc default
  CpuObserver observer;
  const double cpu_start = ClockSeconds(CLOCK_PROCESS_CPUTIME_ID);
  absl::StatusOr<ReconstructionReport> report = RunReconstruction(
      options, {source, gate, sink, observer}, ErrorContext{}, CancelToken::Never());
  if (!report.ok()) {
    std::fprintf(stderr, "reconstruct %lld: %s\n", static_cast<long long>(points),
                 report.status().ToString().c_str());
    return row;
  }
  const ReconstructionReport& r = *report;
  row.cpu = ClockSeconds(CLOCK_PROCESS_CPUTIME_ID) - cpu_start;
  row.faces = r.mesh.faces;
  row.voxel_size = r.voxel_size;
  for (int k = 0; k < 3; ++k) row.grid[k] = r.grid[k];
  row.voxels = int64_t{r.grid[0]} * r.grid[1] * r.grid[2];
  row.bits = r.quantization.bits;
  const double s[] = {r.seconds.decode,  r.seconds.voxelize, r.seconds.shrink,
                      r.seconds.relax,   r.seconds.surface,  r.seconds.decimate,
                      r.seconds.check,   r.seconds.encode};
  static_assert(sizeof s / sizeof s[0] == kStages, "one wall time per PipelineStage");
  for (int k = 0; k < kStages; ++k) {
    row.seconds[k] = s[k];
    row.cpu_seconds[k] = observer.seconds[k];
  }
  row.total = r.seconds.total;
  row.peak_rss = r.peak_rss_bytes;
  row.ok = true;
  return row;
}

int Main(int argc, char** argv) {
  Options o;
  if (!ParseArgs(argc, argv, o)) {
    std::fputs(kUsage, stderr);
    return 2;
  }
  std::printf("bench_scale: %s, threads %d, %d output bits%s, load %s\n", o.shape.c_str(),
              o.threads, o.bits, o.bits_follow_voxel ? " or more as the voxel needs" : "",
              LoadAverage().c_str());
  std::vector<Row> rows;
  bool failed = false;
  for (int64_t n : o.points) {
    Row row = RunInChild<Row>([&] { return RunOne(o, n); });
    if (!row.ok) {
      std::printf("%lld points: FAILED\n", static_cast<long long>(n));
      failed = true;
      continue;
    }
    rows.push_back(row);
    std::printf(
        "%lld points: grid %dx%dx%d (%.3g voxels), voxel %.5g, %lld faces, file bits %d; "
        "total %.2f s wall, %.2f s CPU, peak RSS %.1f MB; load %s\n",
        static_cast<long long>(row.points), row.grid[0], row.grid[1], row.grid[2],
        static_cast<double>(row.voxels), row.voxel_size, static_cast<long long>(row.faces),
        row.bits, row.total, row.cpu, row.peak_rss / 1e6, LoadAverage().c_str());
    std::fflush(stdout);
  }
  if (rows.empty()) return 1;
  // The table: per stage, per count, wall and CPU seconds, CPU us/point and us/face, and the
  // ratio of CPU us/point (voxelize, shrink) or us/face (the rest) to the first count's.
  std::printf("\n%-9s", "stage");
  for (const Row& r : rows)
    std::printf(" | %9lld pts: wall s  cpu s us/pt us/face  x1st",
                static_cast<long long>(r.points));
  std::printf("\n");
  for (int k = 0; k <= kStages; ++k) {
    std::printf("%-9s", k < kStages ? PipelineStageName(static_cast<PipelineStage>(k)) : "total");
    auto cpu = [k](const Row& r) { return k < kStages ? r.cpu_seconds[k] : r.cpu; };
    for (const Row& r : rows) {
      const double wall = k < kStages ? r.seconds[k] : r.total;
      const double per_point = 1e6 * cpu(r) / static_cast<double>(r.points);
      const double per_face = 1e6 * cpu(r) / static_cast<double>(std::max<int64_t>(r.faces, 1));
      // Voxelize and the shrink follow the cloud.
      const bool by_point = k == static_cast<int>(PipelineStage::kVoxelize) ||
                            k == static_cast<int>(PipelineStage::kShrink);
      const double first =
          1e6 * cpu(rows[0]) /
          static_cast<double>(by_point ? rows[0].points : std::max<int64_t>(rows[0].faces, 1));
      const double here = by_point ? per_point : per_face;
      std::printf(" | %21.2f %6.2f %5.2f %7.2f %5.2f", wall, cpu(r), per_point, per_face,
                  first > 0 ? here / first : 0.0);
    }
    std::printf("\n");
  }
  std::printf("%-9s", "peak RSS");
  for (const Row& r : rows)
    std::printf(" | %21.1f MB %8.0f B/pt %9.2f", r.peak_rss / 1e6,
                static_cast<double>(r.peak_rss) / r.points,
                (static_cast<double>(r.peak_rss) / r.points) /
                    (static_cast<double>(rows[0].peak_rss) / rows[0].points));
  std::printf("\n");
  return failed ? 1 : 0;
}

}  // namespace
}  // namespace membrane::bench

int main(int argc, char** argv) {
  // The executables' malloc settings, so that each stage costs here what it costs in membrane.
  membrane::RestartWithHugePageHeap("/proc/self/exe", argv);
  membrane::KeepFreedBlocksInOneHeap();
  return membrane::bench::Main(argc, argv);
}
