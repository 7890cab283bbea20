// How far a Draco decode in a child process has come (DecodeInSubprocess). Draco's decoder
// cannot count its own work, and it writes nothing before it has decoded everything; what the
// parent can see is the child's CPU time and, at the end, its points arriving. Decoding takes
// CPU in proportion to the coded bytes (the child waits on nothing but its input, which it has
// whole before it starts), so the decoder's share of the fraction is its CPU time against the
// time those bytes take, and the points read back are the rest.
#ifndef MEMBRANE_CORE_IO_DECODE_PROGRESS_H_
#define MEMBRANE_CORE_IO_DECODE_PROGRESS_H_

#include <sys/types.h>

#include <cstddef>
#include <cstdint>
#include <optional>

#include "core/base/progress_meter.h"

namespace membrane {

// CPU seconds Draco 1.5.5 takes per coded byte, about: 0.23 s for a 2.0 MB 2M-point torus,
// 0.05 s for a 0.7 MB 500k-point sphere (median of 2 runs each; wall was 8-10 times that on the
// loaded 2-core test machine, which is why the share counts CPU and not wall time).
inline constexpr double kDecoderCpuSecondsPerByte = 1e-7;
// The part of the stage the decoder's own work covers; the points read back cover the rest.
inline constexpr double kDecoderShare = 0.9;

// The CPU time (user and system) process `pid` has used, in clock ticks (sysconf(_SC_CLK_TCK)
// a second), from /proc/PID/stat; -1 when it cannot be read (no /proc, the process is gone).
int64_t ProcessCpuTicks(pid_t pid);

// Counts one decode on `range`: [0, kDecoderShare] by the child's CPU time against
// `input_bytes` x kDecoderCpuSecondsPerByte (held at kDecoderShare when the decoder takes
// longer), then the rest by the bytes of the point list read back, once its count has arrived.
// The fraction never goes back; the caller ends the range (ProgressRange::Done) once the result
// is checked. Used from one thread, the one that talks to the child.
class DecodeProgress {
 public:
  // `child`: the decoder's pid.
  DecodeProgress(ProgressRange range, size_t input_bytes, pid_t child);

  // Counts what has happened since the last call: the child's CPU time while it decodes, then
  // the `output_bytes` of its standard output so far (a little-endian uint64 point count, then
  // 12 bytes a point), once `point_count`, that count, has come. Reads /proc only while the
  // count has not come and `range` counts.
  void Update(uint64_t output_bytes, std::optional<uint64_t> point_count);

 private:
  const ProgressRange range_;
  const pid_t child_;
  int64_t cpu_ticks_ = 0;      // counted so far
  bool reading_points_ = false;  // the second step has begun
  uint64_t bytes_counted_ = 0;  // of the output, in the second step
};

}  // namespace membrane

#endif  // MEMBRANE_CORE_IO_DECODE_PROGRESS_H_
