#include "client/progress_printer.h"

#include <unistd.h>

namespace membrane::client {
namespace {

// Carriage return, then "erase to end of line": a shorter text must not leave the tail of a
// longer one behind.
constexpr char kRewriteLine[] = "\r\033[K";

}  // namespace

ProgressPrinter::ProgressPrinter(std::FILE* out, Mode mode) : out_(out), mode_(mode) {}

ProgressPrinter::~ProgressPrinter() { EndLiveLine(); }

ProgressPrinter::Mode ProgressPrinter::StderrMode(bool quiet) {
  if (quiet) return Mode::kQuiet;
  return isatty(STDERR_FILENO) ? Mode::kLive : Mode::kLines;
}

void ProgressPrinter::Update(absl::string_view text) {
  switch (mode_) {
    case Mode::kQuiet:
      return;
    case Mode::kLines:
      std::fprintf(out_, "%.*s\n", static_cast<int>(text.size()), text.data());
      break;
    case Mode::kLive:
      std::fprintf(out_, "%s%.*s", kRewriteLine, static_cast<int>(text.size()), text.data());
      live_line_open_ = true;
      break;
  }
  std::fflush(out_);
}

void ProgressPrinter::Finish(absl::string_view text) {
  Update(text);
  EndLiveLine();
}

void ProgressPrinter::EndLiveLine() {
  if (!live_line_open_) return;
  std::fputc('\n', out_);
  std::fflush(out_);
  live_line_open_ = false;
}

}  // namespace membrane::client
