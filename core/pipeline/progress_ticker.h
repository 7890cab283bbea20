// The pipeline's side of StageProgress: the meter the running stage counts its work on, and a
// thread that tells the observer how the stage is doing on the observer's schedule.
#ifndef MEMBRANE_CORE_PIPELINE_PROGRESS_TICKER_H_
#define MEMBRANE_CORE_PIPELINE_PROGRESS_TICKER_H_

#include <chrono>
#include <condition_variable>
#include <mutex>
#include <optional>
#include <thread>

#include "core/base/progress_meter.h"
#include "core/pipeline/reconstruction_observer.h"

namespace membrane {

// Stands between the stages and the caller's observer: every call is passed on under one
// mutex, so that the observer never sees two at once, and a thread of its own (only when the
// observer has a progress_schedule) calls StageProgress while a stage runs past the
// schedule's first_after_seconds, and once more before that stage's StageFinished. Each
// StageStarted resets the meter for the new stage. Where no thread can be started, the run
// goes on without progress.
class ProgressTicker : public ReconstructionObserver {
 public:
  // `observer` (not owned) must outlive the ticker.
  explicit ProgressTicker(ReconstructionObserver& observer);
  // Stops and joins the thread.
  ~ProgressTicker() override;

  ProgressTicker(const ProgressTicker&) = delete;
  ProgressTicker& operator=(const ProgressTicker&) = delete;

  // The running stage's meter, for the stage to count its work on.
  ProgressRange progress() { return ProgressRange(&meter_); }

  void StageStarted(PipelineStage stage, const ReconstructionReport& report) override;
  void GenerationFinished(const GenerationStats& generation, int planned_generations) override;
  void StageFinished(PipelineStage stage, double seconds,
                     const ReconstructionReport& report) override;

 private:
  using Clock = std::chrono::steady_clock;

  void Run();
  // Tells the observer how the running stage is doing; mutex_ held.
  void TellLocked(double seconds);

  ReconstructionObserver& observer_;
  const std::optional<ProgressSchedule> schedule_;
  ProgressMeter meter_;
  std::mutex mutex_;
  std::condition_variable wake_;
  bool stopping_ = false;                // guarded by mutex_
  std::optional<PipelineStage> stage_;  // the running stage; guarded by mutex_
  Clock::time_point started_;            // of stage_; guarded by mutex_
  bool told_ = false;                    // StageProgress called for stage_; guarded by mutex_
  std::thread thread_;
};

}  // namespace membrane

#endif  // MEMBRANE_CORE_PIPELINE_PROGRESS_TICKER_H_
