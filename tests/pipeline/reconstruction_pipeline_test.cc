// The pipeline is the one driver of a reconstruction: it runs and reports all its stages,
// asks its gate before it allocates, returns its adapters' errors as they are and its own in
// the caller's words, stops between stages when cancelled, and writes the float32 mesh again
// when the output grid crosses faces.
#include <algorithm>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "core/mesh/output_grid.h"
#include "core/pipeline/in_memory_ends.h"
#include "core/pipeline/reconstruction_pipeline.h"
#include "core/synth/synthesize.h"

namespace membrane::testing {
namespace {

using ::testing::ElementsAreArray;
using ::testing::HasSubstr;

PointCloud SampledSphere(int64_t points = 10000) {
  absl::StatusOr<PointCloud> cloud =
      SynthesizeShape(SynthOptions{.shape = "sphere", .points = points, .seed = 5});
  EXPECT_TRUE(cloud.ok()) << cloud.status();
  return cloud.value_or(PointCloud{});
}

// Records the events as "started decode", "finished decode", ... (generations left out).
class EventLog : public ReconstructionObserver {
 public:
  void StageStarted(PipelineStage stage, const ReconstructionReport&) override {
    events.push_back(std::string("started ") + PipelineStageName(stage));
  }
  void GenerationFinished(const GenerationStats&, int) override { ++generations; }
  void StageFinished(PipelineStage stage, double, const ReconstructionReport&) override {
    events.push_back(std::string("finished ") + PipelineStageName(stage));
  }
  std::vector<std::string> events;
  int generations = 0;
};

// What the gate was asked, with a status to answer each question.
class RecordingGate : public ResourceGate {
 public:
  absl::Status AdmitGrid(const PlannedGrid& grid, int64_t points,
                         const CancelToken&) override {
    asked_grid = grid;
    asked_points = points;
    if (cancel_at_grid != nullptr) cancel_at_grid->Cancel();
    return grid_answer;
  }
  absl::Status AdmitSurface(const MembraneCounts& membrane, const CancelToken&) override {
    asked_membrane = membrane;
    ++surface_questions;
    if (cancel_at_surface != nullptr) cancel_at_surface->Cancel();
    return surface_answer;
  }
  absl::Status grid_answer, surface_answer;
  CancelToken* cancel_at_grid = nullptr;
  CancelToken* cancel_at_surface = nullptr;
  PlannedGrid asked_grid;
  int64_t asked_points = 0;
  MembraneCounts asked_membrane;
  int surface_questions = 0;
};

class FailingSource : public CloudSource {
 public:
  explicit FailingSource(absl::Status status) : status_(std::move(status)) {}
  absl::StatusOr<PointCloud> Read(const CancelToken&, ProgressRange) override { return status_; }

 private:
  absl::Status status_;
};

// Keeps the mesh, but refuses the origin or the write when told to.
class RefusingSink : public InMemoryMeshSink {
 public:
  absl::Status CheckOrigin(const Origin3d&) override { return origin_answer; }
  absl::Status Write(const TriangleMesh& mesh, const PositionGrid& grid) override {
    if (!write_answer.ok()) return write_answer;
    return InMemoryMeshSink::Write(mesh, grid);
  }
  absl::Status origin_answer, write_answer;
};

// Words the tests can find: the pipeline adds them to its own errors only.
const ErrorContext kContext{.invalid_argument_prefix = "cloud.xyz: ",
                            .resource_exhausted_advice = "; try a larger voxel"};

struct Outcome {
  absl::StatusOr<ReconstructionReport> report;
  EventLog log;
};

Outcome RunWith(CloudSource& source, ResourceGate& gate, MeshSink& sink,
            const ReconstructionOptions& options = {},
            const CancelToken& cancel = CancelToken::Never()) {
  Outcome run;
  run.report = RunReconstruction(options, {source, gate, sink, run.log}, kContext, cancel);
  return run;
}

TEST(ReconstructionPipeline, RunsAndReportsEveryStageFromSourceToSink) {
  const PointCloud cloud = SampledSphere();
  InMemoryCloudSource source(cloud);
  RecordingGate gate;
  InMemoryMeshSink sink;
  const Outcome run = RunWith(source, gate, sink);
  ASSERT_TRUE(run.report.ok()) << run.report.status();
  const ReconstructionReport& r = *run.report;
  const std::vector<std::string> stages = {"decode", "voxelize", "shrink", "relax",
                                           "surface", "check", "encode"};
  std::vector<std::string> expected;
  for (const std::string& s : stages) {
    expected.push_back("started " + s);
    expected.push_back("finished " + s);
  }
  EXPECT_THAT(run.log.events, ElementsAreArray(expected));
  EXPECT_EQ(run.log.generations, static_cast<int>(r.generations.size()));

  EXPECT_EQ(r.points, static_cast<int64_t>(cloud.points.size()));
  EXPECT_GT(r.seconds.decode, 0);
  EXPECT_GT(r.seconds.encode, 0);
  EXPECT_GE(r.seconds.total, r.seconds.decode + r.seconds.voxelize + r.seconds.shrink +
                                 r.seconds.relax + r.seconds.surface);
  EXPECT_GT(r.peak_rss_bytes, 0);

  // The sink holds the mesh the check judged: closed, a sphere.
  EXPECT_EQ(sink.writes(), 1);
  EXPECT_EQ(static_cast<int64_t>(sink.mesh().faces.size()), r.mesh.faces);
  EXPECT_TRUE(r.mesh.closed && r.mesh.manifold && r.mesh.oriented);
  EXPECT_EQ(r.mesh.shells, 1);
  EXPECT_EQ(r.mesh.genus, std::vector<int>{0});

  // The gate was asked about the grid the run then allocated, and about its membrane.
  EXPECT_EQ(gate.asked_points, r.points);
  EXPECT_EQ(gate.asked_grid.voxel_size, r.voxel_size);
  EXPECT_EQ(gate.asked_grid.voxels, int64_t{r.grid[0]} * r.grid[1] * r.grid[2]);
  EXPECT_EQ(gate.surface_questions, 1);
  EXPECT_EQ(gate.asked_membrane.membrane_voxels(), r.membrane.membrane_voxels());
}

// With a face budget, the decimate stage runs between the surface and the check, and the
// check judges (and the sink gets) the decimated mesh, on the output grid.
TEST(ReconstructionPipeline, ATargetFaceCountDecimatesBeforeTheCheck) {
  InMemoryCloudSource source(SampledSphere());
  NoResourceLimit gate;
  InMemoryMeshSink sink;
  ReconstructionOptions options;
  options.target_faces = 500;
  options.output_quantization_bits = 11;
  const Outcome run = RunWith(source, gate, sink, options);
  ASSERT_TRUE(run.report.ok()) << run.report.status();
  const ReconstructionReport& r = *run.report;
  const std::vector<std::string> stages = {"decode", "voxelize", "shrink", "relax",  "surface",
                                           "decimate", "check",  "encode"};
  std::vector<std::string> expected;
  for (const std::string& s : stages) {
    expected.push_back("started " + s);
    expected.push_back("finished " + s);
  }
  EXPECT_THAT(run.log.events, ElementsAreArray(expected));
  ASSERT_TRUE(r.decimation.ran);
  EXPECT_GT(r.decimation.stats.faces_before, 10 * 500);
  EXPECT_LE(r.decimation.stats.faces_after, 500);
  EXPECT_EQ(r.mesh.faces, r.decimation.stats.faces_after);
  EXPECT_EQ(static_cast<int64_t>(sink.mesh().faces.size()), r.mesh.faces);
  EXPECT_TRUE(r.mesh.closed && r.mesh.manifold && r.mesh.oriented && r.mesh.positive_volume);
  EXPECT_EQ(r.mesh.self_intersections, 0);
  EXPECT_EQ(r.mesh.genus, std::vector<int>{0});
  EXPECT_EQ(r.quantization.bits, 11);
  for (const Point3f& p : sink.mesh().vertices) ASSERT_EQ(sink.grid().Snap(p), p);
  // The sphere has radius 1: the error is a small part of it, and measured.
  EXPECT_GT(r.decimation.error.max, 0);
  EXPECT_LT(r.decimation.error.max, 0.05);
  EXPECT_LE(r.decimation.error.mean, r.decimation.error.max);
  EXPECT_GT(r.seconds.decimate, 0);
  EXPECT_TRUE(r.warnings.empty());
}

TEST(ReconstructionPipeline, ATargetBelowTheTopologysLeastIsInvalidArgument) {
  {
    InMemoryCloudSource source(SampledSphere());
    NoResourceLimit gate;
    InMemoryMeshSink sink;
    ReconstructionOptions options;
    options.target_faces = 3;
    const Outcome run = RunWith(source, gate, sink, options);
    EXPECT_EQ(run.report.status().code(), absl::StatusCode::kInvalidArgument);
    EXPECT_THAT(std::string(run.report.status().message()),
                ::testing::StartsWith("cloud.xyz: target of 3 faces: it must be at least 4"));
    EXPECT_TRUE(run.log.events.empty());  // refused before any work
  }
  {
    absl::StatusOr<PointCloud> spheres =
        SynthesizeShape(SynthOptions{.shape = "two-spheres", .points = 40000, .seed = 5});
    ASSERT_TRUE(spheres.ok()) << spheres.status();
    InMemoryCloudSource source(*spheres);
    NoResourceLimit gate;
    InMemoryMeshSink sink;
    ReconstructionOptions options;
    options.target_faces = 6;
    const Outcome run = RunWith(source, gate, sink, options);
    EXPECT_EQ(run.report.status().code(), absl::StatusCode::kInvalidArgument);
    EXPECT_THAT(std::string(run.report.status().message()),
                HasSubstr("below the 8 faces that the surface's 2 shells of genus 0, 0 need"));
    EXPECT_EQ(sink.writes(), 0);
  }
}

TEST(ReconstructionPipeline, AdaptersErrorsAreReturnedAsTheyAre) {
  {
    const absl::Status source_error = absl::InvalidArgumentError("scan.drc: not Draco");
    FailingSource source(source_error);
    NoResourceLimit gate;
    InMemoryMeshSink sink;
    const Outcome run = RunWith(source, gate, sink);
    EXPECT_EQ(run.report.status(), source_error);
    EXPECT_THAT(run.log.events, ElementsAreArray({"started decode"}));
  }
  {
    InMemoryCloudSource source(SampledSphere());
    NoResourceLimit gate;
    RefusingSink sink;
    sink.origin_answer = absl::InvalidArgumentError("out.stl: cannot hold the origin");
    const Outcome run = RunWith(source, gate, sink);
    EXPECT_EQ(run.report.status(), sink.origin_answer);
    EXPECT_THAT(run.log.events, ElementsAreArray({"started decode", "finished decode"}));
  }
  {
    InMemoryCloudSource source(SampledSphere());
    RecordingGate gate;
    gate.grid_answer = absl::ResourceExhaustedError("the grid needs too much");
    InMemoryMeshSink sink;
    const Outcome run = RunWith(source, gate, sink);
    EXPECT_EQ(run.report.status(), gate.grid_answer);
    EXPECT_THAT(run.log.events, ElementsAreArray({"started decode", "finished decode"}));
  }
  {
    InMemoryCloudSource source(SampledSphere());
    RecordingGate gate;
    gate.surface_answer = absl::ResourceExhaustedError("the surface needs too much");
    InMemoryMeshSink sink;
    const Outcome run = RunWith(source, gate, sink);
    EXPECT_EQ(run.report.status(), gate.surface_answer);
    ASSERT_FALSE(run.log.events.empty());
    EXPECT_EQ(run.log.events.back(), "finished relax");
    EXPECT_EQ(sink.writes(), 0);
  }
  {
    InMemoryCloudSource source(SampledSphere());
    NoResourceLimit gate;
    RefusingSink sink;
    sink.write_answer = absl::InvalidArgumentError("out.ply: permission denied");
    const Outcome run = RunWith(source, gate, sink);
    EXPECT_EQ(run.report.status(), sink.write_answer);
    // The check and the encode are reported, the write failed or not.
    ASSERT_GE(run.log.events.size(), 2u);
    EXPECT_EQ(run.log.events.back(), "finished encode");
  }
}

TEST(ReconstructionPipeline, ItsOwnErrorsGetTheCallersWords) {
  {
    PointCloud equal;
    equal.points.assign(10, Point3f{1, 2, 3});
    InMemoryCloudSource source(std::move(equal));
    NoResourceLimit gate;
    InMemoryMeshSink sink;
    const Outcome run = RunWith(source, gate, sink);
    EXPECT_EQ(run.report.status().code(), absl::StatusCode::kInvalidArgument);
    EXPECT_THAT(std::string(run.report.status().message()),
                ::testing::StartsWith("cloud.xyz: all 10 points are equal"));
  }
  {
    InMemoryCloudSource source(SampledSphere());
    NoResourceLimit gate;
    InMemoryMeshSink sink;
    ReconstructionOptions options;
    options.voxelize.voxel_budget = 1000;
    const Outcome run = RunWith(source, gate, sink, options);
    EXPECT_EQ(run.report.status().code(), absl::StatusCode::kResourceExhausted);
    EXPECT_THAT(std::string(run.report.status().message()),
                AllOf(HasSubstr("over the voxel budget of 1e+03"),
                      ::testing::EndsWith("; try a larger voxel")));
  }
  {
    // Whatever the gate admits, a grid over the memory ceiling is refused before it is made.
    InMemoryCloudSource source(SampledSphere());
    NoResourceLimit gate;
    InMemoryMeshSink sink;
    ReconstructionOptions options;
    options.memory_ceiling_bytes = 1000;
    const Outcome run = RunWith(source, gate, sink, options);
    EXPECT_EQ(run.report.status().code(), absl::StatusCode::kResourceExhausted);
    EXPECT_THAT(std::string(run.report.status().message()),
                AllOf(HasSubstr("voxels: with the"), HasSubstr("more than the ceiling of 1 KB"),
                      ::testing::EndsWith("; try a larger voxel")));
    EXPECT_EQ(run.log.events.back(), "finished decode");  // nothing voxelized
  }
  {
    InMemoryCloudSource source(SampledSphere());
    NoResourceLimit gate;
    InMemoryMeshSink sink;
    ReconstructionOptions options;
    options.threads = 0;
    const Outcome run = RunWith(source, gate, sink, options);
    EXPECT_EQ(run.report.status(),
              absl::InvalidArgumentError("cloud.xyz: threads is 0; it must be in 1..256"));
    EXPECT_TRUE(run.log.events.empty());  // refused before any work
  }
}

TEST(ReconstructionPipeline, ACancelStopsAtTheNextStage) {
  {
    CancelToken cancel;
    InMemoryCloudSource source(SampledSphere());
    RecordingGate gate;
    gate.cancel_at_grid = &cancel;  // fires while the grid is admitted
    InMemoryMeshSink sink;
    const Outcome run = RunWith(source, gate, sink, {}, cancel);
    EXPECT_EQ(run.report.status().code(), absl::StatusCode::kCancelled);
    EXPECT_THAT(run.log.events, ::testing::Not(::testing::Contains("started shrink")));
  }
  {
    CancelToken cancel;
    InMemoryCloudSource source(SampledSphere());
    RecordingGate gate;
    gate.cancel_at_surface = &cancel;  // fires while the surface is admitted
    InMemoryMeshSink sink;
    const Outcome run = RunWith(source, gate, sink, {}, cancel);
    EXPECT_EQ(run.report.status(), absl::CancelledError("reconstruction cancelled after relax"));
    EXPECT_EQ(sink.writes(), 0);
  }
}

// A 1-bit grid holds 8 positions: no surface of a sphere keeps its faces apart there, so the
// pipeline builds it again in float32. The snapped cuberille has flattened faces, known before
// any check: it is neither checked nor written, only the float32 mesh is.
TEST(ReconstructionPipeline, AGridThatCrossesFacesIsLeftForFloat32) {
  InMemoryCloudSource source(SampledSphere(1000));
  NoResourceLimit gate;
  InMemoryMeshSink sink;
  ReconstructionOptions options;
  options.surface = SurfaceKind::kCuberille;
  options.output_quantization_bits = 1;
  const Outcome run = RunWith(source, gate, sink, options);
  ASSERT_TRUE(run.report.ok()) << run.report.status();
  EXPECT_EQ(run.report->quantization.requested_bits, 1);
  EXPECT_EQ(run.report->quantization.bits, 0);
  EXPECT_EQ(sink.writes(), 1);
  EXPECT_TRUE(sink.grid().lossless());
  EXPECT_TRUE(run.report->mesh.closed);
  EXPECT_EQ(run.report->mesh.self_intersections, 0);
  EXPECT_EQ(run.report->mesh.degenerate_faces, 0);
  EXPECT_EQ(std::count(run.log.events.begin(), run.log.events.end(), "finished surface"), 2);
  EXPECT_EQ(std::count(run.log.events.begin(), run.log.events.end(), "finished check"), 1);
  EXPECT_EQ(std::count(run.log.events.begin(), run.log.events.end(), "finished encode"), 1);
}

// Bits left to the reconstruction follow the voxel: 4 bits over a sphere's grid would step
// several voxels at a time, so the surface is built on the fewest bits whose step is within
// kMaxOutputStepVoxels; asked for as they are, the 4 bits stand (or give float32).
TEST(ReconstructionPipeline, OutputBitsLeftToItFollowTheVoxel) {
  // The quantization report of a 4-bit run of the sphere, and the bits its sink was given.
  const auto run_at_four_bits = [](bool follow_voxel, int* sink_bits) {
    ReconstructionOptions options;
    options.output_quantization_bits = 4;
    options.output_bits_follow_voxel = follow_voxel;
    InMemoryCloudSource source(SampledSphere());
    NoResourceLimit gate;
    InMemoryMeshSink sink;
    const Outcome run = RunWith(source, gate, sink, options);
    EXPECT_TRUE(run.report.ok()) << run.report.status();
    *sink_bits = sink.grid().bits;
    return run.report.ok() ? *run.report : ReconstructionReport{};
  };
  int sink_bits = -1;
  const ReconstructionReport followed = run_at_four_bits(true, &sink_bits);
  const QuantizationReport& q = followed.quantization;
  EXPECT_EQ(q.requested_bits, 4);
  EXPECT_GT(q.bits, 4);
  EXPECT_EQ(sink_bits, q.bits);
  EXPECT_LE(q.step, kMaxOutputStepVoxels * followed.voxel_size);
  EXPECT_LE(q.max_position_error, 0.5 * kMaxOutputStepVoxels * followed.voxel_size);
  EXPECT_TRUE(followed.mesh.closed);
  EXPECT_EQ(followed.mesh.self_intersections, 0);

  const ReconstructionReport as_asked = run_at_four_bits(false, &sink_bits);
  EXPECT_EQ(as_asked.quantization.requested_bits, 4);
  EXPECT_TRUE(as_asked.quantization.bits == 4 || as_asked.quantization.bits == 0)
      << as_asked.quantization.bits;
}

// The fit's crease test discounts the points' noise whether the voxel size is the default or
// given: a given size measures the noise for the surface itself (the report keeps 0), and the
// fit makes the same targets. Without it every vertex of a noisy cloud was tried as a crease.
TEST(ReconstructionPipeline, AGivenVoxelSizeFitsCreasesAsTheDefaultSizeDoes) {
  // A sphere cut flat by a cap (its rim a crease), with noise of 0.15 voxel.
  absl::StatusOr<PointCloud> cloud = SynthesizeShape(
      SynthOptions{.shape = "capped-sphere", .points = 60000, .noise = 0.003, .seed = 3});
  ASSERT_TRUE(cloud.ok()) << cloud.status();
  InMemoryCloudSource source(*cloud);
  RecordingGate gate;
  InMemoryMeshSink sink;
  const Outcome automatic = RunWith(source, gate, sink);
  ASSERT_TRUE(automatic.report.ok()) << automatic.report.status();
  ASSERT_GT(automatic.report->point_noise, 0);
  ReconstructionOptions given;
  given.voxelize.voxel_size = automatic.report->voxel_size;
  InMemoryCloudSource again(*cloud);
  const Outcome explicit_size = RunWith(again, gate, sink, given);
  ASSERT_TRUE(explicit_size.report.ok()) << explicit_size.report.status();
  EXPECT_EQ(explicit_size.report->point_noise, 0);
  const FitTargetCounts& a = automatic.report->fit;
  const FitTargetCounts& e = explicit_size.report->fit;
  EXPECT_GT(a.quadric, 0);
  EXPECT_EQ(e.quadric, a.quadric);
  EXPECT_EQ(e.plane, a.plane);
  EXPECT_EQ(e.crease, a.crease);
  EXPECT_EQ(e.crease_line, a.crease_line);
  EXPECT_EQ(e.umbrella, a.umbrella);
}


}  // namespace
}  // namespace membrane::testing
