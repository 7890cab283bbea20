// What a running reconstruction tells whoever watches it: a terminal printer in the client, a
// job's event stream in the server.
#ifndef MEMBRANE_CORE_PIPELINE_RECONSTRUCTION_OBSERVER_H_
#define MEMBRANE_CORE_PIPELINE_RECONSTRUCTION_OBSERVER_H_

#include "core/engine/membrane_shrinker.h"
#include "core/pipeline/pipeline_stage.h"
#include "core/pipeline/reconstruction_report.h"

namespace membrane {

// Called on the reconstructing thread, in order; an implementation must return quickly (the
// shrink waits for it) and must not throw.
class ReconstructionObserver {
 public:
  virtual ~ReconstructionObserver() = default;

  // `stage` begins; `report` holds what the stages before it measured (for kShrink,
  // planned_generations is set).
  virtual void StageStarted(PipelineStage stage, const ReconstructionReport& report) = 0;
  // One plate generation of the shrink ended; `generation` is its row of the statistics,
  // `planned_generations` how many the schedule plans in all.
  virtual void GenerationFinished(const GenerationStats& generation, int planned_generations) = 0;
  // `stage` ended after `seconds` (also in report.seconds); `report` holds its measurements.
  virtual void StageFinished(PipelineStage stage, double seconds,
                             const ReconstructionReport& report) = 0;
};

// An observer that ignores everything: for callers that want no progress.
class NullReconstructionObserver : public ReconstructionObserver {
 public:
  void StageStarted(PipelineStage, const ReconstructionReport&) override {}
  void GenerationFinished(const GenerationStats&, int) override {}
  void StageFinished(PipelineStage, double, const ReconstructionReport&) override {}
};

}  // namespace membrane

#endif  // MEMBRANE_CORE_PIPELINE_RECONSTRUCTION_OBSERVER_H_
