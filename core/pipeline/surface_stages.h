// The pipeline's stages from the final membrane to the mesh delivered (paper section 6): build
// the surface on the output grid, then check it while the mesh sink encodes or writes it.
// Each tells the observer when it starts and ends and records its measurements and wall
// seconds in the report. Only RunReconstruction calls them, on the reconstructing thread.
#ifndef MEMBRANE_CORE_PIPELINE_SURFACE_STAGES_H_
#define MEMBRANE_CORE_PIPELINE_SURFACE_STAGES_H_

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "core/base/cancel_token.h"
#include "core/base/progress_meter.h"
#include "core/engine/voxel_grid.h"
#include "core/geometry/point_cloud.h"
#include "core/geometry/position_grid.h"
#include "core/pipeline/mesh_sink.h"
#include "core/pipeline/reconstruction_observer.h"
#include "core/pipeline/reconstruction_options.h"
#include "core/pipeline/reconstruction_report.h"
#include "core/pipeline/surface_builder.h"

namespace membrane {

// The surface of the final membrane `grid` (BuildSurface of options.surface, fitted to
// `cloud`), its positions on `output_grid`; the grid and the mesh's size in `report`. `grid`
// is given up: the smooth surface cleans it in place and frees it (left empty). A second
// call (the float32 fallback) adds its seconds to the first's. Cancelled within milliseconds
// of `cancel` firing during the smooth surface. `progress` counts the surface's work
// (BuildSurface) once StageStarted has been told. `point_noise` is the points' noise across
// their surface (model units; 0 when unknown), which the fit's crease test discounts.
absl::StatusOr<BuiltSurface> SurfaceStage(const ReconstructionOptions& options,
                                          const CancelToken& cancel, VoxelGrid&& grid,
                                          const PointCloud& cloud,
                                          const PositionGrid& output_grid,
                                          ReconstructionReport& report,
                                          ReconstructionObserver& observer, double point_noise,
                                          ProgressRange progress = ProgressRange());

// InvalidArgument "no surface: ..." for a membrane that gave an empty mesh: at its voxel size
// (in `report`) the cloud's points are too few or too far apart to hold one.
absl::Status EmptySurfaceError(const ReconstructionReport& report);

// The check stage and the encode stage at once: checks `surface` into report.mesh on a thread
// of its own (with `threads`) while `sink` writes it, on `grid`, on this thread; then reports
// the check and the encode, each with its own wall seconds (which overlap). The sink's status
// as it is. A second call (the float32 fallback) adds its seconds to the first's. `progress`
// counts the check's work (CheckMesh); the encode's is not counted (Draco cannot tell).
absl::Status CheckAndWriteStage(const BuiltSurface& surface, const PositionGrid& grid,
                                int threads, const CancelToken& cancel, MeshSink& sink,
                                ReconstructionReport& report, ReconstructionObserver& observer,
                                ProgressRange progress = ProgressRange());

}  // namespace membrane

#endif  // MEMBRANE_CORE_PIPELINE_SURFACE_STAGES_H_
