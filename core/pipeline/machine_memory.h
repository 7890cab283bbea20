// How much memory this process may use: the machine's, or its container's when a cgroup limit
// is lower. The server takes its default memory budget from it and `membrane reconstruct
// --local` its default memory limit, so that a noisy cloud is refused with a message instead
// of being killed by the kernel's OOM killer halfway.
#ifndef MEMBRANE_CORE_PIPELINE_MACHINE_MEMORY_H_
#define MEMBRANE_CORE_PIPELINE_MACHINE_MEMORY_H_

#include <cstdint>
#include <optional>
#include <string>

#include "absl/strings/string_view.h"

namespace membrane {

struct MachineMemory {
  // The most this process could have: MemTotal, or the lowest cgroup memory limit on its path
  // when lower. 0: unknown (no /proc/meminfo).
  int64_t total_bytes = 0;
  // What it can have now without swapping: MemAvailable, or the lowest cgroup limit when
  // lower. Not the limit minus the cgroup's usage: that usage counts the page cache, which the
  // kernel gives back under pressure, so a container that had read a large file would seem
  // full. 0: unknown.
  int64_t available_bytes = 0;
  // Where total_bytes comes from: "MemTotal" or "cgroup <path>"; "unknown" when 0.
  std::string total_source = "unknown";
};

// The files read, as paths; tests point them into a scratch tree.
struct MachineMemoryFiles {
  std::string meminfo = "/proc/meminfo";
  std::string self_cgroup = "/proc/self/cgroup";  // "ID:controllers:path" lines
  std::string cgroup_root = "/sys/fs/cgroup";     // v2 unified, or v1 with a memory/ directory
};

// Reads `files`. cgroup v2 ("0::/path": memory.max) and v1 ("N:memory:/path":
// memory/.../memory.limit_in_bytes) are both understood; every level
// from the process's cgroup up to the root counts, since a parent's limit binds its children.
// A container usually sees its own cgroup as the root of a namespaced mount: the path from
// /proc/self/cgroup is then absent and the mount's root files hold its limit. "max" and v1's
// near-2^63 "no limit" values are no limit. Unreadable or malformed files count as absent:
// never an error, at worst a zero (unknown) field.
MachineMemory ReadMachineMemory(const MachineMemoryFiles& files = {});

// The value in bytes of the /proc/meminfo line "`key`: N kB" in `meminfo`; nullopt when absent
// or malformed.
std::optional<int64_t> MemInfoBytes(absl::string_view meminfo, absl::string_view key);

// A cgroup memory file's value ("max", or a byte count, with or without a trailing newline):
// nullopt for "max", values of 2^62 or more (v1's way of saying none), and anything malformed.
std::optional<int64_t> CgroupBytes(absl::string_view text);

}  // namespace membrane

#endif  // MEMBRANE_CORE_PIPELINE_MACHINE_MEMORY_H_
