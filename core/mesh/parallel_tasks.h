// Numbered tasks spread over a few threads, for the loops of the surface and the mesh check
// whose iterations are independent (the crossing search's cells, the fit's slabs).
#ifndef MEMBRANE_CORE_MESH_PARALLEL_TASKS_H_
#define MEMBRANE_CORE_MESH_PARALLEL_TASKS_H_

#include <cstdint>

#include "absl/functional/function_ref.h"

namespace membrane {

// Calls task(worker, t) once for every t in [0, tasks), on min(threads, tasks) threads: the
// calling thread is worker 0, the others are started for the call and joined before it
// returns. Tasks are handed out in increasing order as workers come free, so which worker runs
// which task is not fixed: `task` must write only what task t owns (plus per-worker scratch
// indexed by `worker`, which is < max(threads, 1)), and a caller that wants the same result
// for any thread count must make it independent of that assignment. threads <= 1 runs every
// task on the calling thread, in order. When the system refuses a thread, the call goes on
// with the workers it has.
void RunTasks(int threads, int64_t tasks, absl::FunctionRef<void(int worker, int64_t task)> task);

}  // namespace membrane

#endif  // MEMBRANE_CORE_MESH_PARALLEL_TASKS_H_
