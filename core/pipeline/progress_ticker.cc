#include "core/pipeline/progress_ticker.h"

#include <system_error>

namespace membrane {

ProgressTicker::ProgressTicker(ReconstructionObserver& observer)
    : observer_(observer), schedule_(observer.progress_schedule()) {
  if (!schedule_.has_value() || !(schedule_->every_seconds > 0)) return;
  try {
    thread_ = std::thread([this] { Run(); });
  } catch (const std::system_error&) {
    // Out of threads: no progress, the same mesh.
  }
}

ProgressTicker::~ProgressTicker() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
  if (thread_.joinable()) thread_.join();
}

void ProgressTicker::StageStarted(PipelineStage stage, const ReconstructionReport& report) {
  std::lock_guard<std::mutex> lock(mutex_);
  meter_.Reset();
  stage_ = stage;
  started_ = Clock::now();
  told_ = false;
  observer_.StageStarted(stage, report);
  if (thread_.joinable() && schedule_->first_after_seconds <= 0) TellLocked(0);
}

void ProgressTicker::GenerationFinished(const GenerationStats& generation,
                                        int planned_generations) {
  std::lock_guard<std::mutex> lock(mutex_);
  // The shrink counts its work in generations: the share of the planned ones done. A handle
  // retry runs generations again; the meter holds at 1 past the plan.
  if (stage_ == PipelineStage::kShrink && planned_generations > 0) {
    if (!meter_.fraction().has_value()) meter_.BeginStep(0, 1, planned_generations);
    meter_.Add(1);
  }
  observer_.GenerationFinished(generation, planned_generations);
}

void ProgressTicker::StageFinished(PipelineStage stage, double seconds,
                                   const ReconstructionReport& report) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (told_ && stage_ == stage) TellLocked(seconds);
  stage_.reset();
  observer_.StageFinished(stage, seconds, report);
}

void ProgressTicker::TellLocked(double seconds) {
  observer_.StageProgress(*stage_, meter_.fraction(), seconds);
  told_ = true;
}

void ProgressTicker::Run() {
  const auto every = std::chrono::duration<double>(schedule_->every_seconds);
  std::unique_lock<std::mutex> lock(mutex_);
  while (!stopping_) {
    // A wait for the stop, not a sleep: the destructor wakes it at once.
    wake_.wait_for(lock, every, [this] { return stopping_; });
    if (stopping_ || !stage_.has_value()) continue;
    const double seconds = std::chrono::duration<double>(Clock::now() - started_).count();
    if (seconds >= schedule_->first_after_seconds) TellLocked(seconds);
  }
}

}  // namespace membrane
