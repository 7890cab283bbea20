#include "core/pipeline/reconstruction_pipeline.h"

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>

#include "absl/status/status.h"
#include "absl/strings/str_cat.h"
#include "absl/types/span.h"
#include "core/engine/compact_states.h"
#include "core/engine/plate_schedule.h"
#include "core/engine/point_noise.h"
#include "core/pipeline/decimation_stage.h"
#include "core/mesh/mesh_decimation.h"
#include "core/mesh/output_grid.h"
#include "core/pipeline/membrane_counts.h"
#include "core/pipeline/membrane_stages.h"
#include "core/pipeline/memory_estimate.h"
#include "core/pipeline/noise_voxel_note.h"
#include "core/pipeline/peak_memory.h"
#include "core/pipeline/progress_ticker.h"
#include "core/pipeline/stopwatch.h"
#include "core/pipeline/surface_stages.h"
#include "core/pipeline/thread_limits.h"

namespace membrane {
namespace {

absl::Status StopIfCancelled(const CancelToken& cancel, PipelineStage finished_stage) {
  if (!cancel.cancelled()) return absl::OkStatus();
  return absl::CancelledError(
      absl::StrCat("reconstruction cancelled after ", PipelineStageName(finished_stage)));
}

absl::Status CheckOptions(const ReconstructionOptions& options) {
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
  if (options.target_faces != 0 && options.target_faces < kMinTargetFaces) {
    return absl::InvalidArgumentError(absl::StrCat("target of ", options.target_faces,
                                                   " faces: it must be at least ",
                                                   kMinTargetFaces, " (a tetrahedron), or 0 "
                                                   "for the surface as built"));
  }
  return absl::OkStatus();
}

// The decode stage: the source's cloud, its size and origin in `report`.
absl::StatusOr<PointCloud> DecodeStage(CloudSource& source, const CancelToken& cancel,
                                       ReconstructionReport& report,
                                       ReconstructionObserver& observer,
                                       ProgressRange progress) {
  const Stopwatch watch;
  observer.StageStarted(PipelineStage::kDecode, report);
  absl::StatusOr<PointCloud> cloud = source.Read(cancel, progress);
  if (!cloud.ok()) return cloud.status();
  report.points = static_cast<int64_t>(cloud->points.size());
  report.origin = cloud->origin;
  report.seconds.decode = watch.Seconds();
  observer.StageFinished(PipelineStage::kDecode, report.seconds.decode, report);
  return cloud;
}

}  // namespace

absl::StatusOr<ReconstructionReport> RunReconstruction(const ReconstructionOptions& options,
                                                       const PipelineAdapters& adapters,
                                                       const ErrorContext& errors,
                                                       const CancelToken& cancel) {
  const Stopwatch total;
  // The pipeline's own failures get the caller's words; the adapters' have theirs already.
  const auto with_context = [&errors](const absl::Status& s) { return WithErrorContext(s, errors); };
  if (absl::Status s = CheckOptions(options); !s.ok()) return with_context(s);
  // Every call to the caller's observer goes through the ticker, which adds StageProgress.
  ProgressTicker ticker(adapters.observer);
  ReconstructionObserver& observer = ticker;
  ReconstructionReport report;
  report.schedule = PlateScheduleName(options.shrink.schedule);
  report.surface = SurfaceKindName(options.surface);
  report.threads = options.threads;

  absl::StatusOr<PointCloud> cloud =
      DecodeStage(adapters.source, cancel, report, observer, ticker.progress());
  if (!cloud.ok()) return cloud.status();
  if (absl::Status s = adapters.sink.CheckOrigin(cloud->origin); !s.ok()) return s;
  if (absl::Status s = StopIfCancelled(cancel, PipelineStage::kDecode); !s.ok()) return s;

  // Planned before anything is allocated, so that the gate can refuse a grid too large for
  // the memory at hand; the planned voxel size and bounds are passed on, so that Voxelize
  // neither counts (formula (1)) nor checks the points again.
  VoxelizeOptions voxelize = options.voxelize;
  voxelize.threads = options.threads;
  absl::StatusOr<PlannedGrid> plan = PlanGrid(*cloud, voxelize, cancel, options.grid_box);
  if (!plan.ok()) return with_context(plan.status());
  // The gate first: its message names the limit the caller can change. The ceiling then
  // catches what a gate without a limit admits.
  if (absl::Status s = adapters.gate.AdmitGrid(*plan, report.points, cancel); !s.ok()) return s;
  if (absl::Status s = CheckMemoryCeiling(*plan, options.memory_ceiling_bytes); !s.ok()) {
    return with_context(s);
  }
  voxelize.voxel_size = plan->voxel_size;
  report.formula_voxel_size = plan->formula_voxel_size;
  report.point_noise = plan->noise.sigma;
  if (options.voxel_plan && options.voxelize.voxel_size > 0) {
    report.formula_voxel_size = options.voxel_plan->formula_voxel_size;
    report.point_noise = options.voxel_plan->point_noise;
  }
  if (std::optional<std::string> note = NoiseVoxelNote(*plan)) {
    report.warnings.push_back(*std::move(note));
  }
  voxelize.checked_bounds = plan->bounds;

  absl::StatusOr<Voxelization> voxelization =
      VoxelizeStage(voxelize, *cloud, cancel, report, observer, ticker.progress());
  if (!voxelization.ok()) return with_context(voxelization.status());
  if (absl::Status s = StopIfCancelled(cancel, PipelineStage::kVoxelize); !s.ok()) return s;
  VoxelGrid& grid = voxelization->grid;

  if (absl::Status s = ShrinkStage(options, cancel, grid, *cloud, report, observer); !s.ok()) {
    return with_context(s);
  }
  report.membrane = CountMembrane(grid, options.threads);
  if (absl::Status s = StopIfCancelled(cancel, PipelineStage::kShrink); !s.ok()) return s;
  if (options.relax) {
    if (absl::Status s =
            RelaxStage(cancel, options.threads, grid, report, observer, ticker.progress());
        !s.ok())
      return with_context(s);
  }

  if (absl::Status s = adapters.gate.AdmitSurface(report.membrane, cancel); !s.ok()) return s;
  const PipelineStage last = options.relax ? PipelineStage::kRelax : PipelineStage::kShrink;
  if (absl::Status s = StopIfCancelled(cancel, last); !s.ok()) return s;

  report.quantization.requested_bits = options.output_quantization_bits;
  PositionGrid output_grid =
      OutputGrid(grid, options.output_bits_follow_voxel
                           ? OutputBitsForVoxel(grid, options.output_quantization_bits)
                           : options.output_quantization_bits);
  const PositionGrid lossless_grid = OutputGrid(grid, 0);
  // The surface takes the membrane's grid and frees it before its fit (a byte a voxel, 2.2 GB
  // at 10M points, beside the fit's structures at the run's peak); the grid is kept as runs
  // (about a hundredth of its bytes) for a second surface, the float32 fallback.
  const std::array<int, 3> grid_dims = grid.dims();
  const std::array<double, 3> grid_origin = grid.origin();
  const double grid_voxel_size = grid.voxel_size();
  // The fit's crease test discounts the points' noise. A size given without a plan measures
  // none (the report's 0 says the size was not the noise's), so the surface reads it here, at
  // that size: without it every vertex of a noisy scan would be tried as a crease.
  double surface_noise = report.point_noise;
  if (surface_noise == 0 && options.surface == SurfaceKind::kSmooth) {
    surface_noise = MeasurePointNoise(cloud->points, plan->bounds,
                                      kNoiseBoxVoxels / 2 * grid.voxel_size(), cancel)
                        .sigma;
  }
  CompactStates membrane_runs;
  if (!membrane_runs.Encode(grid.states(), cancel, options.threads)) {
    return StopIfCancelled(cancel, last);
  }
  for (;;) {
    if (grid.size() == 0) {
      grid = VoxelGrid(grid_dims, grid_origin, grid_voxel_size);
      if (!membrane_runs.Decode(absl::MakeSpan(grid.mutable_states()), cancel, options.threads)) {
        return StopIfCancelled(cancel, last);
      }
    }
    absl::StatusOr<BuiltSurface> surface =
        SurfaceStage(options, cancel, std::move(grid), *cloud, output_grid, report, observer,
                     surface_noise, ticker.progress());
    if (!surface.ok()) return with_context(surface.status());
    if (absl::Status s = StopIfCancelled(cancel, PipelineStage::kSurface); !s.ok()) return s;
    if (surface->mesh.faces.empty()) return with_context(EmptySurfaceError(report));
    surface->mesh.origin = cloud->origin;  // the mesh is in the cloud's frame
    // A mesh the check would refuse on this grid is built in float32 at once, without a check
    // and an encoding that would both be done again. Not when decimating: the collapses can
    // remove what is broken.
    if (!output_grid.lossless() && options.target_faces == 0 &&
        KnownBroken(*surface, options.threads)) {
      output_grid = lossless_grid;
      continue;
    }
    if (absl::Status s = DecimateStage(options, cancel, output_grid, *surface, report, observer,
                                       ticker.progress());
        !s.ok()) {
      return s.code() == absl::StatusCode::kCancelled ? s : with_context(s);
    }
    if (absl::Status s = CheckAndWriteStage(*surface, output_grid, options.threads, cancel,
                                            adapters.sink, report, observer, ticker.progress());
        !s.ok()) {
      return s;
    }
    const bool broken = report.mesh.self_intersections > 0 || report.mesh.degenerate_faces > 0;
    if (output_grid.lossless() || !broken) break;
    // The grid is too coarse for this surface: no position on it keeps the faces apart.
    output_grid = lossless_grid;
  }
  if (absl::Status s = StopIfCancelled(cancel, PipelineStage::kCheck); !s.ok()) return s;

  report.seconds.total = total.Seconds();
  report.peak_rss_bytes = PeakRssBytes();
  return report;
}

}  // namespace membrane
