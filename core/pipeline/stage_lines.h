// One-line descriptions of a reconstruction's progress, shared by the client's printer and
// the server's events, so that `--local` and `--server` show the same lines.
#ifndef MEMBRANE_CORE_PIPELINE_STAGE_LINES_H_
#define MEMBRANE_CORE_PIPELINE_STAGE_LINES_H_

#include <optional>
#include <string>

#include "core/engine/membrane_shrinker.h"
#include "core/pipeline/pipeline_stage.h"
#include "core/pipeline/reconstruction_report.h"

namespace membrane {

// The line shown while `stage` runs, e.g. "shrink: generation 1/9 ..."; `report` as passed to
// ReconstructionObserver::StageStarted.
std::string StageStartedLine(PipelineStage stage, const ReconstructionReport& report);

// "shrink: generation 3/9, plate size 8: 2100 soft voxels, 150 started contractions, ..."
std::string GenerationLine(const GenerationStats& generation, int planned_generations);

// The outcome of a finished `stage` from the measurements in `report`, e.g.
// "voxelize: grid 164x104x82 (voxel size 0.0123), 19144 hard voxels, ... in 0.020 s".
std::string StageFinishedLine(PipelineStage stage, const ReconstructionReport& report);

// How a running stage is doing: "42% in 1.3 s", or "1.3 s" for a stage that does not count its
// work (`fraction` nullopt). The percentage is rounded down: 100% only once the work is done.
std::string ProgressNote(std::optional<double> fraction, double seconds);

}  // namespace membrane

#endif  // MEMBRANE_CORE_PIPELINE_STAGE_LINES_H_
