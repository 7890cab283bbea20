#include "client/reconstruction_pipeline.h"

#include <utility>

#include "absl/status/status.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "absl/strings/str_join.h"
#include "client/io_errors.h"
#include "client/membrane_counts.h"
#include "client/peak_memory.h"
#include "client/stopwatch.h"
#include "core/engine/plate_schedule.h"
#include "core/io/mesh_io.h"
#include "core/io/point_cloud_io.h"
#include "core/mesh/mesh_check.h"
#include "core/mesh/relaxation.h"

namespace membrane::client {
namespace {

absl::Status StopIfCancelled(const CancelToken& cancel, absl::string_view finished_stage) {
  if (!cancel.cancelled()) return absl::OkStatus();
  return absl::CancelledError(absl::StrCat("reconstruction cancelled after ", finished_stage));
}

absl::StatusOr<PointCloud> Decode(const ReconstructionParams& params, ReconstructionReport& report,
                                  ProgressPrinter& progress) {
  const Stopwatch watch;
  progress.Begin(absl::StrCat("decode: reading ", params.input));
  absl::StatusOr<PointCloud> cloud = ReadPointCloud(params.input);
  if (!cloud.ok()) return FileErrorAsInvalidInput(cloud.status());
  report.points = static_cast<int64_t>(cloud->points.size());
  report.seconds.decode = watch.Seconds();
  progress.Finish(
      absl::StrFormat("decode: %d points in %.3f s", report.points, report.seconds.decode));
  return cloud;
}

absl::StatusOr<Voxelization> VoxelizeCloud(const ReconstructionParams& params,
                                           const PointCloud& cloud, ReconstructionReport& report,
                                           ProgressPrinter& progress) {
  const Stopwatch watch;
  progress.Begin("voxelize: ...");
  absl::StatusOr<Voxelization> v = Voxelize(cloud.points, params.voxelize);
  if (!v.ok()) {
    const absl::Status& s = v.status();
    if (s.code() == absl::StatusCode::kResourceExhausted) {
      return absl::ResourceExhaustedError(
          absl::StrCat(s.message(), "; use a larger --voxel-size or raise --voxel-budget"));
    }
    // Degenerate clouds (no points, all equal, coplanar): name the file they came from.
    return absl::Status(s.code(), absl::StrCat(params.input, ": ", s.message()));
  }
  report.voxel_size = v->grid.voxel_size();
  report.grid = v->grid.dims();
  report.data_grid = v->data_dims;
  report.hard_voxels = v->hard_voxels;
  report.density_ratio = v->density_ratio;
  report.seconds.voxelize = watch.Seconds();
  progress.Finish(absl::StrFormat(
      "voxelize: grid %s (voxel size %.6g), %d hard voxels, density ratio %.3g in %.3f s",
      absl::StrJoin(report.grid, "x"), report.voxel_size, report.hard_voxels, report.density_ratio,
      report.seconds.voxelize));
  return v;
}

absl::Status Shrink(const ReconstructionParams& params, const CancelToken& cancel, VoxelGrid& grid,
                    ReconstructionReport& report, ProgressPrinter& progress) {
  const Stopwatch watch;
  // The shrinker computes the same schedule; asking for it here gives the "3/9" of the
  // progress line without a hook in the engine.
  const size_t total =
      PlateSizes(report.data_grid, params.shrink.schedule, params.shrink.initial_plate).size();
  progress.Begin(absl::StrFormat("shrink: generation 1/%d ...", total));
  const GenerationCallback on_generation = [&](const GenerationStats& g) {
    progress.Update(absl::StrFormat(
        "shrink: generation %d/%d, plate size %d: %d soft voxels, %d started contractions, "
        "%d backtrackings, %.3f s",
        g.generation, total, g.plate_size, g.soft_voxels, g.started_contractions, g.backtrackings,
        g.seconds));
  };
  absl::StatusOr<ShrinkResult> result = ShrinkMembrane(grid, params.shrink, on_generation, &cancel);
  if (!result.ok()) return result.status();
  report.generations = std::move(result->generations);
  report.post_process = result->post_process;
  report.seconds.shrink = watch.Seconds();
  progress.Finish(absl::StrFormat(
      "shrink: %d generations in %.3f s; %d of %d inside hard voxels connected to the membrane",
      report.generations.size(), report.seconds.shrink,
      report.post_process.inside_hard_before - report.post_process.inside_hard_after,
      report.post_process.inside_hard_before));
  return absl::OkStatus();
}

absl::Status RelaxMembrane(const CancelToken& cancel, VoxelGrid& grid, ReconstructionReport& report,
                           ProgressPrinter& progress) {
  const Stopwatch watch;
  progress.Begin("relax: ...");
  absl::StatusOr<RelaxationStats> stats = Relax(grid, [&cancel] { return cancel.cancelled(); });
  if (!stats.ok()) return stats.status();
  report.relaxed = true;
  report.relaxation = *stats;
  report.seconds.relax = watch.Seconds();
  progress.Finish(absl::StrFormat(
      "relax: %d dents filled, %d bumps shaved, %d steps refused to keep the topology in %.3f s",
      stats->phase1_moves, stats->phase2_moves, stats->not_simple, report.seconds.relax));
  return absl::OkStatus();
}

absl::StatusOr<TriangleMesh> Surface(const ReconstructionParams& params, const CancelToken& cancel,
                                     const VoxelGrid& grid, const PointCloud& cloud,
                                     ReconstructionReport& report, ProgressPrinter& progress) {
  const Stopwatch watch;
  progress.Begin(absl::StrCat("surface: ", report.surface, " ..."));
  absl::StatusOr<TriangleMesh> mesh = BuildSurface(grid, cloud, params.surface, &cancel);
  if (!mesh.ok()) return mesh.status();
  report.seconds.surface = watch.Seconds();
  progress.Finish(absl::StrFormat("surface: %s, %d vertices, %d faces in %.3f s", report.surface,
                                  mesh->vertices.size(), mesh->faces.size(),
                                  report.seconds.surface));
  return mesh;
}

void Check(const TriangleMesh& mesh, ReconstructionReport& report, ProgressPrinter& progress) {
  const Stopwatch watch;
  progress.Begin("check: ...");
  report.mesh = CheckMesh(mesh);
  report.seconds.check = watch.Seconds();
  const MeshReport& m = report.mesh;
  progress.Finish(
      absl::StrFormat("check: %s, %s, %s, %d shell(s), genus [%s], %d self-intersections in %.3f s",
                      m.closed ? "closed" : "NOT closed", m.manifold ? "manifold" : "NOT manifold",
                      m.oriented ? "oriented" : "NOT oriented", m.shells,
                      absl::StrJoin(m.genus, ", "), m.self_intersections, report.seconds.check));
}

absl::Status Encode(const ReconstructionParams& params, const TriangleMesh& mesh,
                    ReconstructionReport& report, ProgressPrinter& progress) {
  const Stopwatch watch;
  progress.Begin(absl::StrCat("encode: writing ", params.output));
  if (absl::Status s = WriteMesh(mesh, params.output, params.draco); !s.ok()) {
    return FileErrorAsInvalidInput(s);
  }
  report.seconds.encode = watch.Seconds();
  progress.Finish(absl::StrFormat("encode: %s in %.3f s", params.output, report.seconds.encode));
  return absl::OkStatus();
}

}  // namespace

absl::StatusOr<ReconstructionReport> RunReconstruction(const ReconstructionParams& params,
                                                       const CancelToken& cancel,
                                                       ProgressPrinter& progress) {
  const Stopwatch total;
  ReconstructionReport report;
  report.schedule = PlateScheduleName(params.shrink.schedule);
  report.surface = SurfaceKindName(params.surface);

  absl::StatusOr<PointCloud> cloud = Decode(params, report, progress);
  if (!cloud.ok()) return cloud.status();
  if (absl::Status s = StopIfCancelled(cancel, "decode"); !s.ok()) return s;

  absl::StatusOr<Voxelization> voxelization = VoxelizeCloud(params, *cloud, report, progress);
  if (!voxelization.ok()) return voxelization.status();
  if (absl::Status s = StopIfCancelled(cancel, "voxelize"); !s.ok()) return s;
  VoxelGrid& grid = voxelization->grid;

  if (absl::Status s = Shrink(params, cancel, grid, report, progress); !s.ok()) return s;
  report.membrane = CountMembrane(grid);
  if (absl::Status s = StopIfCancelled(cancel, "shrink"); !s.ok()) return s;

  if (params.relax) {
    if (absl::Status s = RelaxMembrane(cancel, grid, report, progress); !s.ok()) return s;
  }

  absl::StatusOr<TriangleMesh> mesh = Surface(params, cancel, grid, *cloud, report, progress);
  if (!mesh.ok()) return mesh.status();
  if (absl::Status s = StopIfCancelled(cancel, "surface"); !s.ok()) return s;

  Check(*mesh, report, progress);
  if (absl::Status s = StopIfCancelled(cancel, "check"); !s.ok()) return s;

  if (absl::Status s = Encode(params, *mesh, report, progress); !s.ok()) return s;
  report.seconds.total = total.Seconds();
  report.peak_rss_bytes = PeakRssBytes();
  return report;
}

}  // namespace membrane::client
