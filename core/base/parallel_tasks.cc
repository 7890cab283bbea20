#include "core/base/parallel_tasks.h"

#include <algorithm>
#include <atomic>
#include <system_error>
#include <thread>
#include <vector>

namespace membrane {

void RunTasks(int threads, int64_t tasks, absl::FunctionRef<void(int worker, int64_t task)> task) {
  const int workers = static_cast<int>(std::min<int64_t>(std::max(threads, 1), tasks));
  if (workers <= 1) {
    for (int64_t t = 0; t < tasks; ++t) task(0, t);
    return;
  }
  std::atomic<int64_t> next{0};
  auto work = [&](int worker) {
    for (int64_t t = next.fetch_add(1, std::memory_order_relaxed); t < tasks;
         t = next.fetch_add(1, std::memory_order_relaxed))
      task(worker, t);
  };
  std::vector<std::thread> started;
  started.reserve(workers - 1);
  for (int w = 1; w < workers; ++w) {
    // A process out of threads (RLIMIT_NPROC, memory) gets fewer workers, not a crash: the
    // workers that exist take every task.
    try {
      started.emplace_back(work, w);
    } catch (const std::system_error&) {
      break;
    }
  }
  work(0);
  for (std::thread& t : started) t.join();
}

}  // namespace membrane
