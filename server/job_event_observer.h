// A ReconstructionObserver that turns a running reconstruction into the job's events
// (StageEvent, GenerationEvent), which every watcher of the job receives.
#ifndef MEMBRANE_SERVER_JOB_EVENT_OBSERVER_H_
#define MEMBRANE_SERVER_JOB_EVENT_OBSERVER_H_

#include <optional>

#include "core/pipeline/reconstruction_observer.h"
#include "server/job.h"
#include "server/server_metrics.h"

namespace membrane::server {

class JobEventObserver : public ReconstructionObserver {
 public:
  // `job` and `metrics` (not owned; metrics may be null) must outlive the observer. Finished
  // stages are also observed in metrics' membrane_stage_seconds. A stage running longer than
  // `progress_after_seconds` (0: every stage, from its start) reports its progress every
  // second (StageProgress events).
  explicit JobEventObserver(Job& job, ServerMetrics* metrics = nullptr,
                            double progress_after_seconds = 1)
      : job_(job), metrics_(metrics), progress_after_seconds_(progress_after_seconds) {}

  void StageStarted(PipelineStage stage, const ReconstructionReport& report) override;
  void GenerationFinished(const GenerationStats& generation, int planned_generations) override;
  void StageFinished(PipelineStage stage, double seconds,
                     const ReconstructionReport& report) override;
  std::optional<ProgressSchedule> progress_schedule() const override;
  void StageProgress(PipelineStage stage, std::optional<double> fraction,
                     double seconds) override;

 private:
  Job& job_;
  ServerMetrics* metrics_;
  double progress_after_seconds_;
  size_t warnings_sent_ = 0;  // report.warnings already in a StageEvent
};

}  // namespace membrane::server

#endif  // MEMBRANE_SERVER_JOB_EVENT_OBSERVER_H_
