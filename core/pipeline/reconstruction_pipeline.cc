#include "core/pipeline/reconstruction_pipeline.h"

#include <functional>
#include <optional>
#include <string>
#include <system_error>
#include <thread>
#include <utility>

#include "absl/status/status.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "core/engine/plate_schedule.h"
#include "core/mesh/mesh_check.h"
#include "core/mesh/relaxation.h"
#include "core/pipeline/membrane_counts.h"
#include "core/pipeline/peak_memory.h"
#include "core/pipeline/scatter_warning.h"
#include "core/pipeline/stopwatch.h"

namespace membrane {
namespace {

absl::Status StopIfCancelled(const CancelToken& cancel, PipelineStage finished_stage) {
  if (!cancel.cancelled()) return absl::OkStatus();
  return absl::CancelledError(
      absl::StrCat("reconstruction cancelled after ", PipelineStageName(finished_stage)));
}

absl::StatusOr<Voxelization> VoxelizeCloud(const ReconstructionOptions& options,
                                           const PointCloud& cloud, const CancelToken& cancel,
                                           ReconstructionReport& report,
                                           ReconstructionObserver& observer) {
  const Stopwatch watch;
  observer.StageStarted(PipelineStage::kVoxelize, report);
  absl::StatusOr<Voxelization> v = Voxelize(cloud.points, options.voxelize);
  if (!v.ok()) return v.status();
  report.voxel_size = v->grid.voxel_size();
  report.grid = v->grid.dims();
  report.data_grid = v->data_dims;
  report.hard_voxels = v->hard_voxels;
  report.density_ratio = v->density_ratio;
  const PointDensity density{v->voxels_with_one_point, v->voxels_with_more_points};
  if (std::optional<std::string> w =
          ScatterWarning(cloud.points, v->bounds, report.voxel_size, density, cancel)) {
    report.warnings.push_back(*std::move(w));
  }
  report.seconds.voxelize = watch.Seconds();
  observer.StageFinished(PipelineStage::kVoxelize, report.seconds.voxelize, report);
  return v;
}

absl::Status Shrink(const ReconstructionOptions& options, const CancelToken& cancel,
                    VoxelGrid& grid, ReconstructionReport& report,
                    ReconstructionObserver& observer) {
  const Stopwatch watch;
  // The shrinker computes the same schedule; asking for it here gives observers the "3/9"
  // of a generation without a hook in the engine.
  report.planned_generations = static_cast<int>(
      PlateSizes(report.data_grid, options.shrink.schedule, options.shrink.initial_plate).size());
  observer.StageStarted(PipelineStage::kShrink, report);
  const int planned = report.planned_generations;
  const GenerationCallback on_generation = [&observer, planned](const GenerationStats& g) {
    observer.GenerationFinished(g, planned);
  };
  absl::StatusOr<ShrinkResult> result =
      ShrinkMembrane(grid, options.shrink, on_generation, &cancel);
  if (!result.ok()) return result.status();
  report.generations = std::move(result->generations);
  report.post_process = result->post_process;
  report.handle_retry = result->handle_retry;
  report.seconds.shrink = watch.Seconds();
  observer.StageFinished(PipelineStage::kShrink, report.seconds.shrink, report);
  return absl::OkStatus();
}

absl::Status RelaxMembrane(const CancelToken& cancel, VoxelGrid& grid,
                           ReconstructionReport& report, ReconstructionObserver& observer) {
  const Stopwatch watch;
  observer.StageStarted(PipelineStage::kRelax, report);
  absl::StatusOr<RelaxationStats> stats = Relax(grid, [&cancel] { return cancel.cancelled(); });
  if (!stats.ok()) return stats.status();
  report.relaxed = true;
  report.relaxation = *stats;
  report.seconds.relax = watch.Seconds();
  observer.StageFinished(PipelineStage::kRelax, report.seconds.relax, report);
  return absl::OkStatus();
}

absl::StatusOr<BuiltSurface> Surface(const ReconstructionOptions& options,
                                     const CancelToken& cancel, const VoxelGrid& grid,
                                     const PointCloud& cloud, const PositionGrid& output_grid,
                                     ReconstructionReport& report,
                                     ReconstructionObserver& observer) {
  const Stopwatch watch;
  observer.StageStarted(PipelineStage::kSurface, report);
  absl::StatusOr<BuiltSurface> built =
      BuildSurface(grid, cloud, options.surface, output_grid, &cancel, options.threads);
  if (!built.ok()) return built.status();
  report.quantization.bits = output_grid.bits;
  report.quantization.step = output_grid.step();
  report.quantization.max_position_error = output_grid.step() / 2;
  // A second build (see MeshDelivery) adds to the first.
  report.seconds.surface += watch.Seconds();
  // Known now; the check repeats them with the rest of its findings.
  report.mesh.vertices = static_cast<int64_t>(built->mesh.vertices.size());
  report.mesh.faces = static_cast<int64_t>(built->mesh.faces.size());
  observer.StageFinished(PipelineStage::kSurface, report.seconds.surface, report);
  return built;
}

// Why a cloud gave no surface at all: at this voxel size its points are too few, or too far
// apart, to hold the membrane (a handful of points, or a stray point far away that stretches
// the box and so the formula-(1) voxel size). An empty mesh is no answer: say so.
absl::Status EmptySurfaceError(const ReconstructionReport& report) {
  return absl::InvalidArgumentError(absl::StrFormat(
      "no surface: at voxel size %g (a %dx%dx%d grid) the %d points fill only %d voxel%s, too "
      "few to enclose a solid; give a denser cloud, remove stray points far from the object, "
      "or ask for a smaller voxel size",
      report.voxel_size, report.data_grid[0], report.data_grid[1], report.data_grid[2],
      report.points, report.hard_voxels, report.hard_voxels == 1 ? "" : "s"));
}

// Checks `surface` into `report` while `deliver` (if any) runs on the calling thread: the check
// has its own thread, so that the delivery, which encodes, allocates from the calling thread's
// malloc arena, whose pages earlier stages have already faulted in (a fresh arena made Draco's
// encode twice as slow, most of it in page faults).
// Crossings the surface step already searched for are taken, not searched again: the smooth
// surface's fit ends with a search of the whole mesh on its final positions, and repeating it
// was most of the check (0.071 -> 0.020 s on fandisk-variable, 2 threads). Where the check
// does search (cuberille), the search gets all `threads`: it is longer than the encode (0.1 s
// against 0.03 s on a mesh of fandisk-variable's size), and leaving the encode a core of its
// own made the whole run slower (wall 0.366 -> 0.336 s with all threads, 2 cores).
absl::Status CheckAndDeliver(const BuiltSurface& surface, const PositionGrid& grid, int threads,
                             const CancelToken& cancel, const MeshDelivery& deliver,
                             ReconstructionReport& report, ReconstructionObserver& observer) {
  observer.StageStarted(PipelineStage::kCheck, report);
  MeshReport checked;
  double seconds = 0;
  auto check = [&] {
    const Stopwatch watch;
    checked = CheckMesh(surface.mesh, [&cancel] { return cancel.cancelled(); }, threads,
                        surface.crossings ? &*surface.crossings : nullptr);
    seconds = watch.Seconds();
  };
  absl::Status delivered;
  double deliver_seconds = 0;
  if (deliver) {
    // Out of threads, the check runs after the delivery instead of beside it.
    std::thread checker;
    try {
      checker = std::thread(check);
    } catch (const std::system_error&) {
    }
    const Stopwatch watch;
    delivered = deliver(surface.mesh, grid);
    deliver_seconds = watch.Seconds();
    if (checker.joinable()) {
      checker.join();
    } else {
      check();
    }
  } else {
    check();
  }
  report.mesh = checked;
  // A second round (see MeshDelivery) adds to the first, as the surface's does.
  report.seconds.check += seconds;
  observer.StageFinished(PipelineStage::kCheck, seconds, report);
  if (deliver) {
    observer.StageStarted(PipelineStage::kEncode, report);
    report.seconds.encode += deliver_seconds;
    observer.StageFinished(PipelineStage::kEncode, deliver_seconds, report);
  }
  return delivered;
}

}  // namespace

absl::StatusOr<ReconstructionResult> ReconstructCloud(const PointCloud& cloud,
                                                      const ReconstructionOptions& options,
                                                      const CancelToken& cancel,
                                                      ReconstructionObserver& observer,
                                                      const MeshDelivery& deliver) {
  const Stopwatch total;
  if (options.output_quantization_bits < 0 || options.output_quantization_bits > 30) {
    return absl::InvalidArgumentError(absl::StrCat("output quantization is ",
                                                   options.output_quantization_bits,
                                                   " bits; it must be 0 (lossless) or 1..30"));
  }
  if (options.threads < 1 || options.threads > kMaxReconstructionThreads) {
    return absl::InvalidArgumentError(absl::StrCat("threads is ", options.threads,
                                                   "; it must be in 1..",
                                                   kMaxReconstructionThreads));
  }
  ReconstructionResult result;
  ReconstructionReport& report = result.report;
  report.points = static_cast<int64_t>(cloud.points.size());
  report.origin = cloud.origin;
  report.schedule = PlateScheduleName(options.shrink.schedule);
  report.surface = SurfaceKindName(options.surface);
  report.threads = options.threads;

  absl::StatusOr<Voxelization> voxelization =
      VoxelizeCloud(options, cloud, cancel, report, observer);
  if (!voxelization.ok()) return voxelization.status();
  if (absl::Status s = StopIfCancelled(cancel, PipelineStage::kVoxelize); !s.ok()) return s;
  VoxelGrid& grid = voxelization->grid;

  if (absl::Status s = Shrink(options, cancel, grid, report, observer); !s.ok()) return s;
  report.membrane = CountMembrane(grid);
  if (absl::Status s = StopIfCancelled(cancel, PipelineStage::kShrink); !s.ok()) return s;

  if (options.relax) {
    if (absl::Status s = RelaxMembrane(cancel, grid, report, observer); !s.ok()) return s;
  }

  if (options.admit_surface) {
    if (absl::Status s = options.admit_surface(report.membrane); !s.ok()) return s;
    const PipelineStage last = options.relax ? PipelineStage::kRelax : PipelineStage::kShrink;
    if (absl::Status s = StopIfCancelled(cancel, last); !s.ok()) return s;
  }
  report.quantization.requested_bits = options.output_quantization_bits;
  PositionGrid output_grid = OutputGrid(grid, options.output_quantization_bits);
  absl::StatusOr<BuiltSurface> surface;
  for (;;) {
    surface = Surface(options, cancel, grid, cloud, output_grid, report, observer);
    if (!surface.ok()) return surface.status();
    if (absl::Status s = StopIfCancelled(cancel, PipelineStage::kSurface); !s.ok()) return s;
    if (surface->mesh.faces.empty()) return EmptySurfaceError(report);
    surface->mesh.origin = cloud.origin;  // the mesh is in the cloud's frame
    if (absl::Status s = CheckAndDeliver(*surface, output_grid, options.threads, cancel, deliver,
                                         report, observer);
        !s.ok())
      return s;
    const bool broken = report.mesh.self_intersections > 0 || report.mesh.degenerate_faces > 0;
    if (output_grid.lossless() || !broken) break;
    // The grid is too coarse for this surface: no position on it keeps the faces apart.
    output_grid = OutputGrid(grid, 0);
  }
  if (absl::Status s = StopIfCancelled(cancel, PipelineStage::kCheck); !s.ok()) return s;

  result.mesh = std::move(surface->mesh);
  report.seconds.total = total.Seconds();
  report.peak_rss_bytes = PeakRssBytes();
  return result;
}

}  // namespace membrane
