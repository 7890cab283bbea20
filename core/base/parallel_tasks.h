// Numbered tasks spread over a few threads, for the loops whose iterations are independent (the
// voxelization's planes, the fit's slabs, the crossing search's cells).
#ifndef MEMBRANE_CORE_BASE_PARALLEL_TASKS_H_
#define MEMBRANE_CORE_BASE_PARALLEL_TASKS_H_

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <vector>

#include "absl/functional/function_ref.h"
#include "core/base/cancel_token.h"

namespace membrane {

// A pass over a voxel grid of fewer voxels stays on the calling thread: the tasks' rounds and
// thread starts cost more than they share (the 100k-point clouds' grids are 1e6-1e7 voxels).
inline constexpr int64_t kMinSplitGridVoxels = int64_t{1} << 24;

// Calls task(worker, t) once for every t in [0, tasks), on min(threads, tasks) threads: the
// calling thread is worker 0, the others are started for the call and joined before it
// returns. Tasks are handed out in increasing order as workers come free, so which worker runs
// which task is not fixed: `task` must write only what task t owns (plus per-worker scratch
// indexed by `worker`, which is < max(threads, 1)), and a caller that wants the same result
// for any thread count must make it independent of that assignment. threads <= 1 runs every
// task on the calling thread, in order. When the system refuses a thread, the call goes on
// with the workers it has.
void RunTasks(int threads, int64_t tasks, absl::FunctionRef<void(int worker, int64_t task)> task);

// [0, count) cut into `tasks` consecutive ranges of sizes differing by at most one, range t
// being [begin(t), end(t)), for RunTasks(threads, ranges.tasks, ...) over a list whose items
// are independent. A few ranges a thread even out ranges of unequal cost.
struct TaskRanges {
  // `per_thread` ranges a thread (>= 1), at most one an item; one range (the calling thread's)
  // when threads <= 1 or count < min_split. count >= 0; count 0 gives one empty range.
  static TaskRanges Split(int64_t count, int threads, int per_thread, int64_t min_split = 0) {
    const int64_t tasks = threads <= 1 || count < min_split
                              ? 1
                              : std::clamp<int64_t>(int64_t{per_thread} * threads, 1,
                                                    std::max<int64_t>(count, 1));
    return TaskRanges{count, tasks};
  }
  int64_t begin(int64_t t) const { return count * t / tasks; }
  int64_t end(int64_t t) const { return count * (t + 1) / tasks; }

  int64_t count = 0;
  int64_t tasks = 1;
};

// Cancellation inside RunTasks: every worker polls the caller's `cancel` (an atomic flag any
// thread may read), and every worker sees the answer through a shared flag, so that the
// workers all stop at once, whichever of them runs the tasks (on a loaded machine the calling
// thread may get none). `cancel` must outlive this object.
class TaskCancel {
 public:
  TaskCancel(const CancelToken& cancel, int threads, int period)
      : cancel_(cancel), period_(period), since_poll_(std::max(threads, 1), 0) {}
  // Counts one unit of `worker`'s work; every `period` of its units, the worker asks
  // `cancel`. True once it has fired.
  bool Poll(int worker) {
    if (++since_poll_[worker] == period_) {
      since_poll_[worker] = 0;
      if (cancel_.cancelled()) fired_.store(true, std::memory_order_relaxed);
    }
    return fired();
  }
  bool fired() const { return fired_.load(std::memory_order_relaxed); }

 private:
  const CancelToken& cancel_;
  const int period_;
  std::vector<int> since_poll_;  // per worker
  std::atomic<bool> fired_{false};
};

}  // namespace membrane

#endif  // MEMBRANE_CORE_BASE_PARALLEL_TASKS_H_
