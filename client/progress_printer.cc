#include "client/progress_printer.h"

#include <sys/ioctl.h>
#include <unistd.h>

#include "absl/strings/str_cat.h"
#include "core/pipeline/stage_lines.h"

namespace membrane::client {
namespace {

// Carriage return, then "erase to end of line": a shorter text must not leave the tail of a
// longer one behind.
constexpr char kRewriteLine[] = "\r\033[K";

}  // namespace

ProgressPrinter::ProgressPrinter(std::FILE* out, Mode mode) : out_(out), mode_(mode) {
  struct winsize size {};
  if (mode_ == Mode::kLive && ioctl(fileno(out_), TIOCGWINSZ, &size) == 0) columns_ = size.ws_col;
}

ProgressPrinter::~ProgressPrinter() { EndLiveLine(); }

ProgressPrinter::Mode ProgressPrinter::StderrMode(bool quiet) {
  if (quiet) return Mode::kQuiet;
  return isatty(STDERR_FILENO) ? Mode::kLive : Mode::kLines;
}

void ProgressPrinter::Begin(absl::string_view text) {
  status_ = std::string(text);
  if (mode_ == Mode::kLive) Print(text, /*fit_width=*/true);
}

void ProgressPrinter::Update(absl::string_view text) {
  status_ = std::string(text);
  Print(text, /*fit_width=*/true);
}

void ProgressPrinter::Finish(absl::string_view text) {
  status_.clear();
  // In full: the line stays on screen, so wrapping does no harm.
  Print(text, /*fit_width=*/false);
  EndLiveLine();
}

void ProgressPrinter::Progress(absl::string_view stage, std::optional<double> fraction,
                               double seconds) {
  const std::string note = ProgressNote(fraction, seconds);
  if (mode_ == Mode::kLive && !status_.empty()) {
    Print(absl::StrCat(status_, " (", note, ")"), /*fit_width=*/true);
  } else {
    Print(absl::StrCat(stage, ": ", note), /*fit_width=*/true);
  }
}

std::optional<ProgressSchedule> ProgressPrinter::progress_schedule() const {
  switch (mode_) {
    case Mode::kQuiet: return std::nullopt;
    case Mode::kLines: return ProgressSchedule{progress_after_, 2.0};
    case Mode::kLive: return ProgressSchedule{progress_after_, 0.25};
  }
  return std::nullopt;
}

void ProgressPrinter::StageProgress(PipelineStage stage, std::optional<double> fraction,
                                    double seconds) {
  Progress(PipelineStageName(stage), fraction, seconds);
}

void ProgressPrinter::StageStarted(PipelineStage stage, const ReconstructionReport& report) {
  Begin(StageStartedLine(stage, report));
}

void ProgressPrinter::GenerationFinished(const GenerationStats& generation,
                                         int planned_generations) {
  Update(GenerationLine(generation, planned_generations));
}

void ProgressPrinter::StageFinished(PipelineStage stage, double /*seconds*/,
                                    const ReconstructionReport& report) {
  Finish(StageFinishedLine(stage, report));
}

void ProgressPrinter::Print(absl::string_view text, bool fit_width) {
  switch (mode_) {
    case Mode::kQuiet: return;
    case Mode::kLines:
      std::fprintf(out_, "%.*s\n", static_cast<int>(text.size()), text.data());
      break;
    case Mode::kLive:
      // One column short: writing the last column makes some terminals wrap at once.
      if (fit_width && columns_ > 1 && text.size() >= static_cast<size_t>(columns_)) {
        text = text.substr(0, static_cast<size_t>(columns_ - 1));
      }
      std::fprintf(out_, "%s%.*s", kRewriteLine, static_cast<int>(text.size()), text.data());
      live_line_open_ = true;
      break;
  }
  std::fflush(out_);
}

void ProgressPrinter::EndLiveLine() {
  if (!live_line_open_) return;
  std::fputc('\n', out_);
  std::fflush(out_);
  live_line_open_ = false;
}

}  // namespace membrane::client
