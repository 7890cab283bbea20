// bench_memory: the memory estimates (core/pipeline/memory_estimate.h) against the memory a
// run holds. One synthetic shape (default the torus of `membrane synth torus`) at several point
// counts, formula-(1) voxel, each a whole RunReconstruction in a child process of its own to an
// in-memory Draco file. Per stage: the peak RSS while it ran (the kernel's high-water mark,
// reset as the stage starts, through /proc/self/clear_refs), the peak between it and the stage
// before (the membrane's census, the output grid), and the estimate the gates use for it. The
// run's peak is the largest of them, against GridBytesEstimate and SurfaceBytesEstimate, the
// two numbers a gate admits. See README.md.
//
// Exit status 1 when a run fails or the kernel's high-water mark cannot be reset (then no stage
// peak can be told from the run's).

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "absl/strings/numbers.h"
#include "absl/strings/str_split.h"
#include "core/pipeline/draco_mesh_sink.h"
#include "core/pipeline/in_memory_ends.h"
#include "core/pipeline/memory_estimate.h"
#include "core/pipeline/pipeline_stage.h"
#include "core/pipeline/reconstruction_pipeline.h"
#include "core/synth/synthesize.h"
#include "tests/bench/bench_util.h"
#include "tests/bench/child_process.h"
#include "tests/support/uniform_noise.h"

namespace membrane::bench {
namespace {

constexpr char kUsage[] =
    "usage: bench_memory [--points N,N,...] [--shape NAME] [--threads N] [--bits B] [--quick]\n"
    "  --points LIST  point counts (default 100000,1000000)\n"
    "  --shape NAME   a shape of `membrane synth` (default torus), or noise: uniform points in\n"
    "                 a cube (a foam of a membrane, the surface's worst case)\n"
    "  --threads N    ReconstructionOptions::threads, 1..256 (default 1): each thread of the\n"
    "                 relaxation, the surface fit and the check holds working sets of its own\n"
    "  --bits B       output quantization bits, 0..30 (default 11, the .drc default)\n"
    "  --quick        20000 and 60000 points (the ctest smoke)\n";

struct Options {
  std::vector<int64_t> points = {100'000, 1'000'000};
  std::string shape = "torus";
  int threads = 1;
  int bits = 11;
};

constexpr int kStages = static_cast<int>(PipelineStage::kEncode) + 1;

// What one count's child reports back through its pipe.
struct Row {
  int64_t points = 0, voxels = 0, membrane_voxels = 0, faces = 0;
  int64_t start_rss = 0;                // before the synthesized cloud is handed over
  int64_t stage_peak[kStages] = {};     // high-water mark while the stage ran
  int64_t gap_peak[kStages] = {};       // between the stage before and this one
  int64_t stage_estimate[kStages] = {};  // what the estimates say for the stage (0: none)
  int64_t grid_estimate = 0, surface_estimate = 0;
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
    } else {
      return false;
    }
  }
  return true;
}

// A field of /proc/self/status in bytes ("VmHWM", "VmRSS"); 0 when unreadable.
int64_t StatusBytes(const std::string& field) {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line)) {
    if (line.rfind(field + ":", 0) != 0) continue;
    int64_t kb = 0;
    std::vector<std::string> words = absl::StrSplit(line, ' ', absl::SkipWhitespace());
    if (words.size() >= 2 && absl::SimpleAtoi(words[1], &kb)) return kb * 1024;
  }
  return 0;
}

// Sets the high-water mark to the current RSS (Linux 4.0 and later).
bool ResetPeak() {
  std::ofstream clear("/proc/self/clear_refs");
  clear << "5";
  clear.flush();
  return static_cast<bool>(clear);
}

// The high-water mark per stage, and between stages.
class PeakObserver : public ReconstructionObserver {
 public:
  explicit PeakObserver(Row& row) : row_(row) {}
  void StageStarted(PipelineStage stage, const ReconstructionReport&) override {
    const int k = static_cast<int>(stage);
    row_.gap_peak[k] = std::max(row_.gap_peak[k], StatusBytes("VmHWM"));
    reset_ok_ = ResetPeak() && reset_ok_;
  }
  void GenerationFinished(const GenerationStats&, int) override {}
  void StageFinished(PipelineStage stage, double, const ReconstructionReport&) override {
    const int k = static_cast<int>(stage);
    row_.stage_peak[k] = std::max(row_.stage_peak[k], StatusBytes("VmHWM"));
    reset_ok_ = ResetPeak() && reset_ok_;
  }
  bool reset_ok() const { return reset_ok_; }

 private:
  Row& row_;
  bool reset_ok_ = true;
};

// A gate that admits everything and keeps what it was asked, for the estimates' columns.
class RecordingGate : public ResourceGate {
 public:
  absl::Status AdmitGrid(const PlannedGrid& grid, int64_t, const CancelToken&) override {
    plan = grid;
    return absl::OkStatus();
  }
  absl::Status AdmitSurface(const MembraneCounts& m, const CancelToken&) override {
    membrane = m;
    return absl::OkStatus();
  }
  PlannedGrid plan;
  MembraneCounts membrane;
};

// In the child: synthesizes the cloud and reconstructs it.
Row RunOne(const Options& o, int64_t points) {
  Row row;
  row.points = points;
  SynthOptions synth;
  synth.shape = o.shape;
  synth.points = points;
  absl::StatusOr<PointCloud> cloud =
      o.shape == "noise" ? testing::UniformNoise(static_cast<int>(points), 12345)
                         : SynthesizeShape(synth);
  if (!cloud.ok()) {
    std::fprintf(stderr, "synth %s %lld: %s\n", o.shape.c_str(), static_cast<long long>(points),
                 cloud.status().ToString().c_str());
    return row;
  }
  ReconstructionOptions options;
  options.output_quantization_bits = o.bits;
  options.threads = o.threads;
  InMemoryCloudSource source(*std::move(cloud));
  RecordingGate gate;
  DracoMeshSink sink(/*compression_level=*/7);  // the .drc default
  PeakObserver observer(row);
  row.start_rss = StatusBytes("VmRSS");
  if (!ResetPeak()) {
    std::fprintf(stderr, "cannot reset the peak RSS through /proc/self/clear_refs\n");
    return row;
  }
  absl::StatusOr<ReconstructionReport> report = RunReconstruction(
      options, {source, gate, sink, observer}, ErrorContext{}, CancelToken::Never());
  if (!report.ok()) {
    std::fprintf(stderr, "reconstruct %lld: %s\n", static_cast<long long>(points),
                 report.status().ToString().c_str());
    return row;
  }
  row.voxels = gate.plan.voxels;
  row.membrane_voxels = gate.membrane.membrane_voxels();
  row.faces = report->mesh.faces;
  const StageBytes estimate = EstimateStageBytes(gate.plan.voxels, points, gate.membrane);
  row.stage_estimate[static_cast<int>(PipelineStage::kDecode)] = estimate.decode;
  row.stage_estimate[static_cast<int>(PipelineStage::kVoxelize)] = estimate.voxelize;
  row.stage_estimate[static_cast<int>(PipelineStage::kShrink)] = estimate.shrink;
  row.stage_estimate[static_cast<int>(PipelineStage::kRelax)] = estimate.relax;
  row.stage_estimate[static_cast<int>(PipelineStage::kSurface)] = estimate.surface;
  row.stage_estimate[static_cast<int>(PipelineStage::kCheck)] = estimate.check;
  row.grid_estimate = gate.plan.bytes;
  row.surface_estimate = SurfaceBytesEstimate(gate.plan, gate.membrane);
  row.ok = observer.reset_ok();
  return row;
}

double Mb(int64_t bytes) { return static_cast<double>(bytes) / 1e6; }

int Main(int argc, char** argv) {
  Options o;
  if (!ParseArgs(argc, argv, o)) {
    std::fputs(kUsage, stderr);
    return 2;
  }
  std::printf("bench_memory: %s, threads %d, %d output bits, load %s\n", o.shape.c_str(),
              o.threads, o.bits, LoadAverage().c_str());
  bool failed = false;
  for (int64_t n : o.points) {
    const Row r = RunInChild<Row>([&] { return RunOne(o, n); });
    if (!r.ok) {
      std::printf("%lld points: FAILED\n", static_cast<long long>(n));
      failed = true;
      continue;
    }
    std::printf(
        "\n%lld points: %.3g voxels, membrane %lld voxels, %lld faces; RSS with the cloud "
        "before the run %.1f MB\n",
        static_cast<long long>(r.points), static_cast<double>(r.voxels),
        static_cast<long long>(r.membrane_voxels), static_cast<long long>(r.faces),
        Mb(r.start_rss));
    std::printf("%-9s %12s %12s %12s %8s\n", "stage", "before MB", "peak MB", "estimate MB",
                "est/peak");
    int64_t peak = 0;
    for (int k = 0; k < kStages; ++k) {
      const int64_t stage = std::max(r.stage_peak[k], r.gap_peak[k]);
      peak = std::max(peak, stage);
      const int64_t e = r.stage_estimate[k];
      std::printf("%-9s %12.1f %12.1f %12s %8s\n", PipelineStageName(static_cast<PipelineStage>(k)),
                  Mb(r.gap_peak[k]), Mb(r.stage_peak[k]),
                  e > 0 ? std::to_string(static_cast<int64_t>(Mb(e))).c_str() : "-",
                  e > 0 && stage > 0
                      ? std::to_string(static_cast<double>(e) / static_cast<double>(stage))
                            .substr(0, 4)
                            .c_str()
                      : "-");
    }
    const int64_t estimate = std::max(r.grid_estimate, r.surface_estimate);
    std::printf(
        "run: peak %.1f MB; admitted before the grid %.1f MB, before the surface %.1f MB; "
        "largest estimate / peak %.2f; load %s\n",
        Mb(peak), Mb(r.grid_estimate), Mb(r.surface_estimate),
        static_cast<double>(estimate) / static_cast<double>(std::max<int64_t>(peak, 1)),
        LoadAverage().c_str());
    std::fflush(stdout);
  }
  return failed ? 1 : 0;
}

}  // namespace
}  // namespace membrane::bench

int main(int argc, char** argv) { return membrane::bench::Main(argc, argv); }
