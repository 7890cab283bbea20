#include "core/pipeline/machine_memory.h"

#include <fstream>
#include <iterator>
#include <vector>

#include "absl/strings/ascii.h"
#include "absl/strings/numbers.h"
#include "absl/strings/str_split.h"
#include "absl/strings/strip.h"

namespace membrane {
namespace {

// v1 writes "no limit" as the largest page-aligned int64 (9223372036854771712); anything this
// large is no limit on any machine.
constexpr int64_t kNoLimitFloor = int64_t{1} << 62;

// The whole of a small text file (/proc and /sys files report size 0, so no seeking); nullopt
// when it cannot be opened.
std::optional<std::string> ReadSmallFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// The files of one cgroup version's memory controller.
struct CgroupLayout {
  std::string base;   // directory of the hierarchy's root
  std::string path;   // the process's cgroup below it ("/" or "/a/b")
  const char* limit;  // the limit's file name
};

// The memory controller's hierarchy from /proc/self/cgroup: a v1 line naming "memory" wins
// (a hybrid system mounts v2 without that controller); else the v2 line "0::path".
std::optional<CgroupLayout> FindMemoryCgroup(const MachineMemoryFiles& files) {
  const std::optional<std::string> text = ReadSmallFile(files.self_cgroup);
  if (!text) return std::nullopt;
  std::optional<CgroupLayout> v2;
  for (absl::string_view line : absl::StrSplit(*text, '\n', absl::SkipEmpty())) {
    const std::vector<absl::string_view> parts = absl::StrSplit(line, absl::MaxSplits(':', 2));
    if (parts.size() != 3 || parts[2].empty() || parts[2][0] != '/') continue;
    const std::string path(parts[2]);
    if (parts[0] == "0" && parts[1].empty()) {
      v2 = CgroupLayout{files.cgroup_root, path, "memory.max"};
      continue;
    }
    for (absl::string_view controller : absl::StrSplit(parts[1], ','))
      if (controller == "memory")
        return CgroupLayout{files.cgroup_root + "/memory", path, "memory.limit_in_bytes"};
  }
  return v2;
}

}  // namespace

std::optional<int64_t> MemInfoBytes(absl::string_view meminfo, absl::string_view key) {
  for (absl::string_view line : absl::StrSplit(meminfo, '\n', absl::SkipEmpty())) {
    if (!absl::ConsumePrefix(&line, key) || !absl::ConsumePrefix(&line, ":")) continue;
    line = absl::StripAsciiWhitespace(line);
    if (!absl::ConsumeSuffix(&line, "kB")) return std::nullopt;
    int64_t kib = 0;
    if (!absl::SimpleAtoi(absl::StripAsciiWhitespace(line), &kib) || kib < 0 ||
        kib > kNoLimitFloor / 1024)
      return std::nullopt;
    return kib * 1024;
  }
  return std::nullopt;
}

std::optional<int64_t> CgroupBytes(absl::string_view text) {
  text = absl::StripAsciiWhitespace(text);
  int64_t bytes = 0;
  if (!absl::SimpleAtoi(text, &bytes) || bytes < 0 || bytes >= kNoLimitFloor) return std::nullopt;
  return bytes;
}

MachineMemory ReadMachineMemory(const MachineMemoryFiles& files) {
  MachineMemory m;
  if (const std::optional<std::string> meminfo = ReadSmallFile(files.meminfo)) {
    if (std::optional<int64_t> total = MemInfoBytes(*meminfo, "MemTotal")) {
      m.total_bytes = *total;
      m.total_source = "MemTotal";
    }
    if (std::optional<int64_t> available = MemInfoBytes(*meminfo, "MemAvailable"))
      m.available_bytes = *available;
  }
  const std::optional<CgroupLayout> cgroup = FindMemoryCgroup(files);
  if (!cgroup) return m;
  // From the process's cgroup up to the root: "/a/b", "/a", "".
  std::string level = cgroup->path == "/" ? "" : cgroup->path;
  for (;;) {
    const std::string dir = cgroup->base + level;
    const std::optional<std::string> limit_text = ReadSmallFile(dir + "/" + cgroup->limit);
    const std::optional<int64_t> limit = limit_text ? CgroupBytes(*limit_text) : std::nullopt;
    if (limit) {
      if (m.total_bytes == 0 || *limit < m.total_bytes) {
        m.total_bytes = *limit;
        m.total_source = "cgroup " + (level.empty() ? std::string("/") : level);
      }
      if (m.available_bytes == 0 || *limit < m.available_bytes) m.available_bytes = *limit;
    }
    if (level.empty()) break;
    level.resize(level.rfind('/'));
  }
  return m;
}

}  // namespace membrane
