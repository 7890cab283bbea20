// What a running reconstruction tells whoever watches it: a terminal printer in the client, a
// job's event stream in the server.
#ifndef MEMBRANE_CORE_PIPELINE_RECONSTRUCTION_OBSERVER_H_
#define MEMBRANE_CORE_PIPELINE_RECONSTRUCTION_OBSERVER_H_

#include <optional>

#include "core/engine/membrane_shrinker.h"
#include "core/pipeline/pipeline_stage.h"
#include "core/pipeline/reconstruction_report.h"

namespace membrane {

// How often an observer wants to hear how a running stage is doing (StageProgress).
struct ProgressSchedule {
  double first_after_seconds = 1;  // a shorter stage reports nothing; 0: from its start
  double every_seconds = 0.5;      // then this often (> 0)
};

// Called in order, never two calls at once: on the reconstructing thread, except
// StageProgress. An implementation must return quickly (the shrink waits for it) and must not
// throw.
class ReconstructionObserver {
 public:
  virtual ~ReconstructionObserver() = default;

  // How often to call StageProgress; nullopt (the default): never, and the run starts no
  // thread for it. Read once, when the run starts.
  virtual std::optional<ProgressSchedule> progress_schedule() const { return std::nullopt; }
  // `stage` has run for `seconds` and done `fraction` of its work, in [0, 1] and never less
  // than the fraction told before within the stage; nullopt for a stage that does not count
  // its work (encode; decode from a source that does not count, CloudSource::Read). Called per
  // progress_schedule() from a thread of the run's own while the stage runs, and for a stage
  // it was called for, once more as it ends, just before StageFinished (surface and check are
  // then at 1).
  virtual void StageProgress(PipelineStage /*stage*/, std::optional<double> /*fraction*/,
                             double /*seconds*/) {}

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
