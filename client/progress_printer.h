// Live progress of a reconstruction on stderr. On a terminal each stage (and each plate
// generation of the shrink) rewrites one status line in place; otherwise (logs, pipes, tests)
// every update is a plain line, so a log shows the whole history. It observes a local
// reconstruction directly; for a remote one the client feeds it the server's events.
#ifndef MEMBRANE_CLIENT_PROGRESS_PRINTER_H_
#define MEMBRANE_CLIENT_PROGRESS_PRINTER_H_

#include <cstdio>
#include <optional>
#include <string>

#include "absl/strings/string_view.h"
#include "core/pipeline/reconstruction_observer.h"

namespace membrane::client {

class ProgressPrinter : public ReconstructionObserver {
 public:
  enum class Mode {
    kQuiet,  // print nothing
    kLines,  // one plain line per Update and per Finish
    kLive,   // rewrite one terminal line; Finish ends it with a newline
  };

  // Prints to `out` (not owned; must outlive the printer) in `mode`. In kLive mode, Update
  // lines are cut to the terminal's width: a wrapped line could not be rewritten in place.
  ProgressPrinter(std::FILE* out, Mode mode);
  // Ends a pending live line, so that whatever is printed next starts on a fresh line.
  ~ProgressPrinter() override;

  ProgressPrinter(const ProgressPrinter&) = delete;
  ProgressPrinter& operator=(const ProgressPrinter&) = delete;

  // The mode for stderr: kQuiet when `quiet`, kLive when stderr is a terminal, else kLines.
  static Mode StderrMode(bool quiet);

  // Announces a stage that is starting: live, replaces the current line; as lines, prints
  // nothing (the Finish line says it all).
  void Begin(absl::string_view text);
  // Shows `text` as the state of the running stage: live, replaces the current line (cut to
  // the terminal width); as lines, prints it.
  void Update(absl::string_view text);
  // Shows `text` as the outcome of a finished stage and moves to a new line.
  void Finish(absl::string_view text);
  // Shows how the running `stage` is doing (ProgressNote): live, after the current line, as
  // "surface: smooth ... (42% in 1.3 s)"; as lines, its own line "surface: 42% in 1.3 s".
  void Progress(absl::string_view stage, std::optional<double> fraction, double seconds);

  // Stages report progress once they have run this long (default 1 s; 0: from their start, as
  // the tests want it).
  void set_progress_after(double seconds) { progress_after_ = seconds; }

  // ReconstructionObserver: the lines of core/pipeline/stage_lines.h through Begin, Update
  // and Finish.
  void StageStarted(PipelineStage stage, const ReconstructionReport& report) override;
  void GenerationFinished(const GenerationStats& generation, int planned_generations) override;
  void StageFinished(PipelineStage stage, double seconds,
                     const ReconstructionReport& report) override;
  // None when quiet; live, every 0.25 s; as lines, every 2 s (a log needs no more).
  std::optional<ProgressSchedule> progress_schedule() const override;
  void StageProgress(PipelineStage stage, std::optional<double> fraction,
                     double seconds) override;

 private:
  // Writes `text` as the mode wants it; `fit_width` cuts a live line to the terminal width.
  void Print(absl::string_view text, bool fit_width);
  void EndLiveLine();

  std::FILE* out_;
  Mode mode_;
  int columns_ = 0;  // terminal width in kLive mode when known, else 0 (no limit)
  bool live_line_open_ = false;
  std::string status_;  // the last Begin or Update text, until Finish
  double progress_after_ = 1;
};

}  // namespace membrane::client

#endif  // MEMBRANE_CLIENT_PROGRESS_PRINTER_H_
