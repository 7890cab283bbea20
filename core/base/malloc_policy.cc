#include "core/base/malloc_policy.h"

#include <malloc.h>
#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <iterator>

namespace membrane {

void KeepFreedBlocksInOneHeap() {
  // One arena: glibc gives a new thread an arena of its own, and only the main arena's heap
  // can hold a block of more than 64 MB; in another arena such a block is mapped on its own
  // whatever M_MMAP_MAX says. A job's thread would fault in fresh pages for every grid-sized
  // array, and the check's thread beside the encode for its tables (on rocker-arm-scan the
  // check takes 0.23 s with one arena and 0.36 s with glibc's default). Threads hardly
  // contend for it: their small blocks come from per-thread caches, and the big ones are few.
  mallopt(M_ARENA_MAX, 1);
  // No blocks mapped on their own (glibc maps every block of 32 MB and more and unmaps it when
  // freed) and no trim (-1 turns it off): each stage's grid-sized arrays then reuse the pages
  // the stage before freed, where fresh ones are cleared by the kernel and, on a VM that
  // reports free pages to its host, faulted in by the host again.
  mallopt(M_MMAP_MAX, 0);
  mallopt(M_TRIM_THRESHOLD, -1);
}

bool KernelGivesHugePagesOnlyWhenAdvised() {
  std::ifstream file("/sys/kernel/mm/transparent_hugepage/enabled");
  const std::string modes((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  return modes.find("[madvise]") != std::string::npos;
}

std::vector<std::string> TunableNames(const char* tunables) {
  std::vector<std::string> names;
  const std::string value = tunables == nullptr ? "" : tunables;
  for (size_t start = 0; start < value.size();) {
    size_t end = value.find(':', start);
    if (end == std::string::npos) end = value.size();
    const std::string item = value.substr(start, end - start);
    if (!item.empty()) names.push_back(item.substr(0, item.find('=')));
    start = end + 1;
  }
  return names;
}

std::optional<std::string> TunablesWithHugePageHeap(const char* current) {
  for (const std::string& name : TunableNames(current)) {
    if (name == kHugePageTunable) return std::nullopt;
  }
  const std::string tunables = current == nullptr ? "" : current;
  return tunables.empty() ? std::string(kHugePageTunable) + "=1"
                          : tunables + ":" + kHugePageTunable + "=1";
}

void RestartWithHugePageHeap(const char* executable, char** argv) {
  if (!kGlibcMalloc) return;
  const char* current = std::getenv("GLIBC_TUNABLES");
  const std::optional<std::string> tunables = TunablesWithHugePageHeap(current);
  // The environment first: the restarted process (and every child it starts) stops there
  // without reading the kernel's setting again.
  if (!tunables || !KernelGivesHugePagesOnlyWhenAdvised()) return;
  const std::optional<std::string> saved =
      current == nullptr ? std::nullopt : std::optional<std::string>(current);
  if (setenv("GLIBC_TUNABLES", tunables->c_str(), 1) != 0) return;
  execv(executable, argv);
  if (saved) {
    setenv("GLIBC_TUNABLES", saved->c_str(), 1);
  } else {
    unsetenv("GLIBC_TUNABLES");
  }
}

}  // namespace membrane
