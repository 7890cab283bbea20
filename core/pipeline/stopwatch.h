// Wall-clock time of a stage, for the progress lines and the statistics.
#ifndef MEMBRANE_CORE_PIPELINE_STOPWATCH_H_
#define MEMBRANE_CORE_PIPELINE_STOPWATCH_H_

#include <chrono>

namespace membrane {

// Starts on construction; steady_clock, so a clock adjustment never gives negative times.
class Stopwatch {
 public:
  Stopwatch() : start_(std::chrono::steady_clock::now()) {}
  // Seconds since construction.
  double Seconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }

 private:
  std::chrono::steady_clock::time_point start_;
};

}  // namespace membrane

#endif  // MEMBRANE_CORE_PIPELINE_STOPWATCH_H_
