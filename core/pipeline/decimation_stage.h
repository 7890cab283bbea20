// The decimate stage, between the surface and the check: the surface brought down to the face
// budget of ReconstructionOptions::target_faces (mesh_decimation.h), and the error that adds.
// Only RunReconstruction calls it, on the reconstructing thread.
#ifndef MEMBRANE_CORE_PIPELINE_DECIMATION_STAGE_H_
#define MEMBRANE_CORE_PIPELINE_DECIMATION_STAGE_H_

#include "absl/status/status.h"
#include "core/base/cancel_token.h"
#include "core/base/progress_meter.h"
#include "core/geometry/position_grid.h"
#include "core/pipeline/reconstruction_observer.h"
#include "core/pipeline/reconstruction_options.h"
#include "core/pipeline/reconstruction_report.h"
#include "core/pipeline/surface_builder.h"

namespace membrane {

// With options.target_faces 0: nothing (no observer call). Otherwise decimates surface.mesh to
// that many faces, its new vertices on `output_grid`, and records in report.decimation the
// counts and the distance from the surface's vertices before to the mesh after (measured on
// options.threads threads), in report.mesh its new size, in report.seconds.decimate its wall
// seconds (added to, on the float32 fallback's second call). A mesh changed loses its
// surface.crossings (its faces are renumbered; the check searches). Adds a warning when the
// mesh stays above the target (no further collapse keeps the guarantees) or when the surface
// is not closed, oriented and manifold (it is then left as it is).
// Errors: InvalidArgument "target of N faces is below the M faces that the surface's ...
// shells ... need" (DecimateMesh's); Cancelled "reconstruction cancelled after surface" when
// `cancel` fires (polled every few thousand collapses). `progress` counts the faces removed
// toward the target, then the error's measure.
absl::Status DecimateStage(const ReconstructionOptions& options, const CancelToken& cancel,
                           const PositionGrid& output_grid, BuiltSurface& surface,
                           ReconstructionReport& report, ReconstructionObserver& observer,
                           ProgressRange progress = ProgressRange());

}  // namespace membrane

#endif  // MEMBRANE_CORE_PIPELINE_DECIMATION_STAGE_H_
