#include "server/job_event_observer.h"

#include "absl/strings/str_cat.h"
#include "core/pipeline/stage_lines.h"

namespace membrane::server {
namespace {

v1::JobEvent StageEvent(PipelineStage stage, v1::StageEvent::Phase phase, double seconds,
                        std::string line) {
  v1::JobEvent event;
  v1::StageEvent* s = event.mutable_stage();
  s->set_stage(PipelineStageName(stage));
  s->set_phase(phase);
  s->set_seconds(seconds);
  s->set_line(std::move(line));
  return event;
}

}  // namespace

void JobEventObserver::StageStarted(PipelineStage stage, const ReconstructionReport& report) {
  job_.AddEvent(StageEvent(stage, v1::StageEvent::STARTED, 0, StageStartedLine(stage, report)));
}

void JobEventObserver::GenerationFinished(const GenerationStats& g, int planned_generations) {
  v1::JobEvent event;
  v1::GenerationEvent* e = event.mutable_generation();
  e->set_generation(g.generation);
  e->set_planned_generations(planned_generations);
  e->set_plate_size(g.plate_size);
  e->set_soft_voxels(g.soft_voxels);
  e->set_started_contractions(g.started_contractions);
  e->set_backtrackings(g.backtrackings);
  e->set_seconds(g.seconds);
  e->set_handle_retry(g.handle_retry);
  job_.AddEvent(std::move(event));
}

void JobEventObserver::StageFinished(PipelineStage stage, double seconds,
                                     const ReconstructionReport& report) {
  v1::JobEvent event =
      StageEvent(stage, v1::StageEvent::FINISHED, seconds, StageFinishedLine(stage, report));
  for (; warnings_sent_ < report.warnings.size(); ++warnings_sent_)
    event.mutable_stage()->add_warnings(report.warnings[warnings_sent_]);
  job_.AddEvent(std::move(event));
  if (metrics_ != nullptr) metrics_->StageFinished(stage, seconds);
}

std::optional<ProgressSchedule> JobEventObserver::progress_schedule() const {
  // Once a second: enough for a progress bar, little for the job's kept events.
  return ProgressSchedule{.first_after_seconds = progress_after_seconds_, .every_seconds = 1};
}

void JobEventObserver::StageProgress(PipelineStage stage, std::optional<double> fraction,
                                     double seconds) {
  v1::JobEvent event;
  v1::StageProgress* p = event.mutable_progress();
  p->set_stage(PipelineStageName(stage));
  if (fraction.has_value()) p->set_fraction(*fraction);
  p->set_seconds(seconds);
  p->set_line(absl::StrCat(PipelineStageName(stage), ": ", ProgressNote(fraction, seconds)));
  job_.AddEvent(std::move(event));
}

}  // namespace membrane::server
