#include "core/io/decode_progress.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>

namespace membrane {

int64_t ProcessCpuTicks(pid_t pid) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/stat");
  const std::string stat((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  // The command name, in parentheses, may hold spaces: the fields are counted after its end.
  const size_t name_end = stat.rfind(')');
  if (name_end == std::string::npos) return -1;
  std::istringstream fields(stat.substr(name_end + 1));
  std::string field;
  // Fields 3 (state) to 13 come first; 14 and 15 are utime and stime.
  for (int i = 3; i <= 13; ++i) fields >> field;
  int64_t user = -1, system = -1;
  fields >> user >> system;
  if (!fields || user < 0 || system < 0) return -1;
  return user + system;
}

DecodeProgress::DecodeProgress(ProgressRange range, size_t input_bytes, pid_t child)
    : range_(range), child_(child) {
  const double ticks = static_cast<double>(input_bytes) * kDecoderCpuSecondsPerByte *
                       static_cast<double>(sysconf(_SC_CLK_TCK));
  range_.Part(0, kDecoderShare).Begin(std::max<int64_t>(1, std::llround(ticks)));
}

void DecodeProgress::Update(uint64_t output_bytes, std::optional<uint64_t> point_count) {
  if (!range_.counts()) return;
  if (!reading_points_) {
    if (!point_count) {
      const int64_t ticks = ProcessCpuTicks(child_);
      if (ticks > cpu_ticks_) {
        range_.Add(ticks - cpu_ticks_);
        cpu_ticks_ = ticks;
      }
      return;
    }
    // A count past what memory could hold is the parent's to refuse, not the meter's.
    const uint64_t count = *point_count;
    const uint64_t bytes = count > (uint64_t{1} << 58) ? 1 : sizeof count + 12 * count;
    range_.Part(kDecoderShare, 1).Begin(static_cast<int64_t>(bytes));
    reading_points_ = true;
  }
  if (output_bytes > bytes_counted_) {
    range_.Add(static_cast<int64_t>(output_bytes - bytes_counted_));
    bytes_counted_ = output_bytes;
  }
}

}  // namespace membrane
