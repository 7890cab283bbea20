// The progress of long stages: the fraction a stage tells never goes back, and the stages
// that count their work (voxelize, relax, surface, check) end at 1, for both surfaces; a
// source that counts its decode has its fractions told;
// progress is told between a stage's start and its end, never at the same time as another
// call; and counting changes nothing in the mesh.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "core/pipeline/in_memory_ends.h"
#include "core/pipeline/reconstruction_pipeline.h"
#include "core/synth/synthesize.h"

namespace membrane::testing {
namespace {

// A grid fine enough for the torus's relaxation to take a while: 0.3 s on 2 loaded cores,
// told in 36 distinct fractions at the test's millisecond schedule.
constexpr double kLongRelaxVoxel = 0.01;

PointCloud SampledTorus() {
  absl::StatusOr<PointCloud> cloud =
      SynthesizeShape(SynthOptions{.shape = "torus", .points = 20000, .seed = 3});
  EXPECT_TRUE(cloud.ok()) << cloud.status();
  return cloud.value_or(PointCloud{});
}

// Progress from every stage's start (first_after 0), every millisecond, as fractions per stage.
class ProgressLog : public ReconstructionObserver {
 public:
  std::optional<ProgressSchedule> progress_schedule() const override {
    return ProgressSchedule{.first_after_seconds = 0, .every_seconds = 0.001};
  }
  void StageStarted(PipelineStage stage, const ReconstructionReport&) override {
    Enter();
    EXPECT_FALSE(running_.has_value());
    running_ = stage;
    Leave();
  }
  void GenerationFinished(const GenerationStats&, int) override {}
  void StageProgress(PipelineStage stage, std::optional<double> fraction,
                     double seconds) override {
    Enter();
    EXPECT_EQ(running_, stage) << PipelineStageName(stage);
    EXPECT_GE(seconds, 0);
    calls[PipelineStageName(stage)].push_back(fraction);
    Leave();
  }
  void StageFinished(PipelineStage stage, double, const ReconstructionReport&) override {
    Enter();
    EXPECT_EQ(running_, stage);
    running_.reset();
    Leave();
  }

  std::map<std::string, std::vector<std::optional<double>>> calls;

 private:
  // The pipeline promises one call at a time: a second thread inside would see `inside_` set.
  void Enter() { EXPECT_FALSE(inside_.exchange(true)); }
  void Leave() { inside_.store(false); }

  std::atomic<bool> inside_{false};
  std::optional<PipelineStage> running_;
};

TEST(StageProgress, FractionsNeverGoBackAndLongStagesEndAtOne) {
  const PointCloud cloud = SampledTorus();
  for (SurfaceKind surface : {SurfaceKind::kSmooth, SurfaceKind::kCuberille}) {
    SCOPED_TRACE(SurfaceKindName(surface));
    InMemoryCloudSource source(cloud);
    NoResourceLimit gate;
    InMemoryMeshSink sink;
    ProgressLog log;
    ReconstructionOptions options;
    options.surface = surface;
    options.threads = 2;
    const absl::StatusOr<ReconstructionReport> report =
        RunReconstruction(options, {source, gate, sink, log}, ErrorContext{}, CancelToken::Never());
    ASSERT_TRUE(report.ok()) << report.status();
    // Every stage is told from its start (first_after 0), and so once more at its end.
    for (const char* stage : {"decode", "voxelize", "shrink", "relax", "surface", "check",
                              "encode"}) {
      EXPECT_GE(log.calls[stage].size(), 2u) << stage;
    }
    for (const auto& [stage, fractions] : log.calls) {
      double last = 0;
      for (const std::optional<double>& f : fractions) {
        if (!f.has_value()) continue;
        EXPECT_GE(*f, last) << stage;
        EXPECT_LE(*f, 1.0) << stage;
        last = *f;
      }
    }
    for (const char* stage : {"voxelize", "relax", "surface", "check"}) {
      ASSERT_FALSE(log.calls[stage].empty());
      EXPECT_EQ(log.calls[stage].back(), std::optional<double>(1.0)) << stage;
    }
    // The shrink counts its generations against the planned ones.
    ASSERT_FALSE(log.calls["shrink"].empty());
    ASSERT_TRUE(log.calls["shrink"].back().has_value());
    EXPECT_GT(*log.calls["shrink"].back(), 0.5);
    // The stages that do not count their work say so.
    EXPECT_EQ(log.calls["encode"].back(), std::nullopt);
  }
}

// A relaxation of many voxels is told in steps: its DLC passes, then each phase's scan and the
// voxels it takes, so a watcher sees it move rather than a bare time.
TEST(StageProgress, ALongRelaxationReportsIncreasingFractions) {
  InMemoryCloudSource source(SampledTorus());
  NoResourceLimit gate;
  InMemoryMeshSink sink;
  ProgressLog log;
  ReconstructionOptions options;
  options.voxelize.voxel_size = kLongRelaxVoxel;
  options.surface = SurfaceKind::kCuberille;
  const absl::StatusOr<ReconstructionReport> report =
      RunReconstruction(options, {source, gate, sink, log}, ErrorContext{}, CancelToken::Never());
  ASSERT_TRUE(report.ok()) << report.status();
  const std::vector<std::optional<double>>& fractions = log.calls["relax"];
  std::vector<double> inside;  // the distinct fractions strictly between 0 and 1, in order
  for (const std::optional<double>& f : fractions) {
    // Only a tick before the first pass begins has no fraction yet.
    if (!f.has_value()) {
      EXPECT_TRUE(inside.empty());
      continue;
    }
    if (*f > 0 && *f < 1 && (inside.empty() || *f != inside.back())) inside.push_back(*f);
  }
  EXPECT_GE(inside.size(), 3u) << "seconds: " << report->seconds.relax
                                << ", ticks: " << fractions.size();
  for (size_t i = 1; i < inside.size(); ++i) EXPECT_GT(inside[i], inside[i - 1]);
  EXPECT_EQ(fractions.back(), std::optional<double>(1.0));
}

// A decode in kSteps steps that goes on to the next only once the observer has been told the
// fraction of the one before: a decode as long as the test wants, on any machine, without a
// sleep. The observer's side records the decode's fractions and wakes the source.
class GatedDecode : public CloudSource, public ReconstructionObserver {
 public:
  static constexpr int kSteps = 4;

  explicit GatedDecode(PointCloud cloud) : cloud_(std::move(cloud)) {}

  absl::StatusOr<PointCloud> Read(const CancelToken&, ProgressRange progress) override {
    progress.Begin(kSteps);
    for (int step = 1; step <= kSteps; ++step) {
      progress.Add(1);
      if (step == kSteps) break;  // the last is told as the stage ends
      std::unique_lock<std::mutex> lock(mutex_);
      const double reached = static_cast<double>(step) / kSteps;
      // A bound on the wait, for a run that never tells: the test then fails instead of hanging.
      if (!told_.wait_for(lock, std::chrono::seconds(60), [&] { return seen_ >= reached; })) {
        ADD_FAILURE() << "the decode's fraction " << reached << " was never told";
        break;
      }
    }
    return cloud_;
  }

  std::optional<ProgressSchedule> progress_schedule() const override {
    return ProgressSchedule{.first_after_seconds = 0, .every_seconds = 0.001};
  }
  void StageProgress(PipelineStage stage, std::optional<double> fraction, double) override {
    if (stage != PipelineStage::kDecode) return;
    std::lock_guard<std::mutex> lock(mutex_);
    fractions.push_back(fraction);
    if (fraction.has_value()) seen_ = std::max(seen_, *fraction);
    told_.notify_all();
  }
  void StageStarted(PipelineStage, const ReconstructionReport&) override {}
  void GenerationFinished(const GenerationStats&, int) override {}
  void StageFinished(PipelineStage, double, const ReconstructionReport&) override {}

  std::vector<std::optional<double>> fractions;  // the decode's, as told

 private:
  const PointCloud cloud_;
  std::mutex mutex_;
  std::condition_variable told_;
  double seen_ = 0;  // the largest decode fraction told
};

TEST(StageProgress, ALongDecodeReportsIncreasingFractions) {
  GatedDecode decode(SampledTorus());
  NoResourceLimit gate;
  InMemoryMeshSink sink;
  ReconstructionOptions options;
  options.surface = SurfaceKind::kCuberille;
  const absl::StatusOr<ReconstructionReport> report =
      RunReconstruction(options, {decode, gate, sink, decode}, ErrorContext{},
                        CancelToken::Never());
  ASSERT_TRUE(report.ok()) << report.status();
  std::vector<double> distinct;  // the distinct fractions told, in order
  for (const std::optional<double>& f : decode.fractions) {
    // Only a tick before the source begins counting has no fraction.
    if (!f.has_value()) {
      EXPECT_TRUE(distinct.empty());
      continue;
    }
    // 0 when a tick falls between the source's Begin and its first Add.
    if (*f > 0 && (distinct.empty() || *f != distinct.back())) distinct.push_back(*f);
  }
  // Each step's fraction, told while the decode ran, then 1 as it ended.
  const std::vector<double> steps = {0.25, 0.5, 0.75, 1.0};
  EXPECT_EQ(distinct, steps);
}

TEST(StageProgress, DecimationCountsItsFacesToTheEnd) {
  InMemoryCloudSource source(SampledTorus());
  NoResourceLimit gate;
  InMemoryMeshSink sink;
  ProgressLog log;
  ReconstructionOptions options;
  options.target_faces = 2000;
  const absl::StatusOr<ReconstructionReport> report =
      RunReconstruction(options, {source, gate, sink, log}, ErrorContext{}, CancelToken::Never());
  ASSERT_TRUE(report.ok()) << report.status();
  const std::vector<std::optional<double>>& fractions = log.calls["decimate"];
  ASSERT_GE(fractions.size(), 2u);
  double last = 0;
  for (const std::optional<double>& f : fractions) {
    if (!f.has_value()) continue;
    EXPECT_GE(*f, last);
    last = *f;
  }
  EXPECT_EQ(fractions.back(), std::optional<double>(1.0));
}

TEST(StageProgress, CountingLeavesTheMeshAsItIs) {
  const PointCloud cloud = SampledTorus();
  std::vector<TriangleMesh> meshes;
  for (bool watched : {false, true}) {
    InMemoryCloudSource source(cloud);
    NoResourceLimit gate;
    InMemoryMeshSink sink;
    ProgressLog log;
    NullReconstructionObserver none;
    ReconstructionObserver& observer = watched ? static_cast<ReconstructionObserver&>(log) : none;
    ReconstructionOptions options;
    options.threads = 2;
    ASSERT_TRUE(
        RunReconstruction(options, {source, gate, sink, observer}, ErrorContext{},
                          CancelToken::Never())
            .ok());
    meshes.push_back(sink.mesh());
  }
  EXPECT_EQ(meshes[0].vertices, meshes[1].vertices);
  EXPECT_EQ(meshes[0].faces, meshes[1].faces);
}

}  // namespace
}  // namespace membrane::testing
