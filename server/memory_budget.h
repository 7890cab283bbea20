// The memory budget across running jobs (--memory-budget-bytes): a job reserves its estimate
// before allocating its grid and waits while others hold the rest.
#ifndef MEMBRANE_SERVER_MEMORY_BUDGET_H_
#define MEMBRANE_SERVER_MEMORY_BUDGET_H_

#include <cstdint>

#include "absl/base/thread_annotations.h"
#include "absl/status/status.h"
#include "absl/synchronization/mutex.h"
#include "core/engine/cancel_token.h"

namespace membrane::server {

class MemoryBudget {
 public:
  // `total_bytes` <= 0: no limit (every reservation succeeds at once).
  explicit MemoryBudget(int64_t total_bytes) : total_(total_bytes) {}

  // Reserves `bytes`, waiting while other jobs hold too much. ResourceExhausted naming both
  // numbers when `bytes` alone exceeds the budget; Cancelled when `cancel` fires while
  // waiting (looked at every 50 ms).
  absl::Status Reserve(int64_t bytes, const CancelToken& cancel) ABSL_LOCKS_EXCLUDED(mutex_);
  // Gives back a reservation.
  void Release(int64_t bytes) ABSL_LOCKS_EXCLUDED(mutex_);

 private:
  const int64_t total_;
  absl::Mutex mutex_;
  int64_t reserved_ ABSL_GUARDED_BY(mutex_) = 0;
};

// An estimate of the peak bytes of one job: the voxel grid and the working sets of the
// shrink and the surface (a few bytes per voxel), plus the cloud and its copies.
int64_t EstimateJobBytes(int64_t voxels, int64_t points);

}  // namespace membrane::server

#endif  // MEMBRANE_SERVER_MEMORY_BUDGET_H_
