// The pipeline's stages that make the membrane (paper sections 2-5): voxelize the cloud,
// shrink the membrane, relax it. Each tells the observer when it starts and ends and records
// its measurements and wall seconds in the report. Only RunReconstruction calls them, on the
// reconstructing thread, in this order.
#ifndef MEMBRANE_CORE_PIPELINE_MEMBRANE_STAGES_H_
#define MEMBRANE_CORE_PIPELINE_MEMBRANE_STAGES_H_

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "core/base/cancel_token.h"
#include "core/base/progress_meter.h"
#include "core/engine/voxel_grid.h"
#include "core/engine/voxelization.h"
#include "core/geometry/point_cloud.h"
#include "core/pipeline/reconstruction_observer.h"
#include "core/pipeline/reconstruction_options.h"
#include "core/pipeline/reconstruction_report.h"

namespace membrane {

// The voxel grid of `cloud` (Voxelize with `voxelize`), its sizes, density and any scatter
// warning in `report`. Voxelize's errors: InvalidArgument for a degenerate cloud,
// ResourceExhausted for a grid over a given voxel budget. `progress` counts Voxelize's work,
// then the scatter test.
absl::StatusOr<Voxelization> VoxelizeStage(const VoxelizeOptions& voxelize,
                                           const PointCloud& cloud, const CancelToken& cancel,
                                           ReconstructionReport& report,
                                           ReconstructionObserver& observer,
                                           ProgressRange progress = ProgressRange());

// Shrinks the membrane of `grid`, voxelized from `cloud` (ShrinkMembrane with options.shrink and
// the cloud's points), each plate generation told to the observer; the generations,
// post-process and handle retry in `report`. Cancelled within milliseconds of `cancel` firing.
absl::Status ShrinkStage(const ReconstructionOptions& options, const CancelToken& cancel,
                         VoxelGrid& grid, const PointCloud& cloud, ReconstructionReport& report,
                         ReconstructionObserver& observer);

// Relaxes the final membrane of `grid` (paper section 5), its grid-wide passes on `threads`
// (the same grid for any count); its counts in `report`, its work on `progress` (Relax's).
// Cancelled within milliseconds of `cancel` firing.
absl::Status RelaxStage(const CancelToken& cancel, int threads, VoxelGrid& grid,
                        ReconstructionReport& report, ReconstructionObserver& observer,
                        ProgressRange progress);

}  // namespace membrane

#endif  // MEMBRANE_CORE_PIPELINE_MEMBRANE_STAGES_H_
