// A ReconstructionObserver that turns a running reconstruction into the job's events
// (StageEvent, GenerationEvent), which every watcher of the job receives.
#ifndef MEMBRANE_SERVER_JOB_EVENT_OBSERVER_H_
#define MEMBRANE_SERVER_JOB_EVENT_OBSERVER_H_

#include "core/pipeline/reconstruction_observer.h"
#include "server/job.h"

namespace membrane::server {

class JobEventObserver : public ReconstructionObserver {
 public:
  // `job` (not owned) must outlive the observer.
  explicit JobEventObserver(Job& job) : job_(job) {}

  void StageStarted(PipelineStage stage, const ReconstructionReport& report) override;
  void GenerationFinished(const GenerationStats& generation, int planned_generations) override;
  void StageFinished(PipelineStage stage, double seconds,
                     const ReconstructionReport& report) override;

 private:
  Job& job_;
  size_t warnings_sent_ = 0;  // report.warnings already in a StageEvent
};

}  // namespace membrane::server

#endif  // MEMBRANE_SERVER_JOB_EVENT_OBSERVER_H_
