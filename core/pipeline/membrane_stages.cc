#include "core/pipeline/membrane_stages.h"

#include <optional>
#include <string>
#include <utility>

#include "core/engine/interior_guard.h"
#include "core/engine/plate_schedule.h"
#include "core/engine/point_density.h"
#include "core/engine/point_noise.h"
#include "core/mesh/relaxation.h"
#include "core/pipeline/scatter_warning.h"
#include "core/pipeline/stopwatch.h"

namespace membrane {

absl::StatusOr<Voxelization> VoxelizeStage(const VoxelizeOptions& voxelize,
                                           const PointCloud& cloud, const CancelToken& cancel,
                                           ReconstructionReport& report,
                                           ReconstructionObserver& observer,
                                           ProgressRange progress) {
  const Stopwatch watch;
  observer.StageStarted(PipelineStage::kVoxelize, report);
  absl::StatusOr<Voxelization> v = Voxelize(cloud.points, voxelize, progress.Part(0, 0.9), cancel);
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
  progress.Part(0.9, 1).Done();
  report.seconds.voxelize = watch.Seconds();
  observer.StageFinished(PipelineStage::kVoxelize, report.seconds.voxelize, report);
  return v;
}

absl::Status ShrinkStage(const ReconstructionOptions& options, const CancelToken& cancel,
                         VoxelGrid& grid, const PointCloud& cloud, ReconstructionReport& report,
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
  // The shrink's word passes share the run's threads (docs/design.md, "Threads").
  ShrinkOptions shrink = options.shrink;
  shrink.threads = options.threads;
  if (VoxelRaisedForNoise(report.formula_voxel_size, report.voxel_size)) {
    shrink.interior_guard = DenseScanGuard(shrink.interior_guard);
  }
  absl::StatusOr<ShrinkResult> result =
      ShrinkMembrane(grid, cloud.points, shrink, on_generation, cancel);
  if (!result.ok()) return result.status();
  report.interior_guard = result->interior_guard;
  report.coarse_plates = result->coarse_plates;
  report.topology_guard = result->guard;
  report.generations = std::move(result->generations);
  report.post_process = result->post_process;
  report.handle_retry = result->handle_retry;
  report.piece_separation = result->separation;
  report.hole_opening = result->holes;
  report.gap_refill = result->refill;
  report.seconds.shrink = watch.Seconds();
  observer.StageFinished(PipelineStage::kShrink, report.seconds.shrink, report);
  return absl::OkStatus();
}

absl::Status RelaxStage(const CancelToken& cancel, int threads, VoxelGrid& grid,
                        ReconstructionReport& report, ReconstructionObserver& observer,
                        ProgressRange progress) {
  const Stopwatch watch;
  observer.StageStarted(PipelineStage::kRelax, report);
  RelaxationOptions relax_options;
  relax_options.threads = threads;
  absl::StatusOr<RelaxationStats> stats = Relax(grid, cancel, relax_options, progress);
  if (!stats.ok()) return stats.status();
  report.relaxed = true;
  report.relaxation = *stats;
  report.seconds.relax = watch.Seconds();
  observer.StageFinished(PipelineStage::kRelax, report.seconds.relax, report);
  return absl::OkStatus();
}

}  // namespace membrane
