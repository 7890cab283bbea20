// The memory budget across running jobs (--memory-budget-bytes): a job reserves its estimate
// before allocating its grid, and the surface's estimate once its membrane is known, and waits
// while others hold the rest (the estimates: core/pipeline/memory_estimate.h).
#ifndef MEMBRANE_SERVER_MEMORY_BUDGET_H_
#define MEMBRANE_SERVER_MEMORY_BUDGET_H_

#include <cstdint>
#include <optional>

#include "absl/base/thread_annotations.h"
#include "absl/status/status.h"
#include "absl/strings/string_view.h"
#include "absl/synchronization/mutex.h"
#include "core/base/cancel_token.h"

namespace membrane::server {

class MemoryBudget {
 public:
  // `total_bytes` <= 0: no limit (every reservation succeeds at once).
  explicit MemoryBudget(int64_t total_bytes) : total_(total_bytes) {}

  // One job's reservation, grown stage by stage and given back whole when destroyed. Must not
  // outlive the budget.
  class Share {
   public:
    explicit Share(MemoryBudget& budget) : budget_(budget) {}
    ~Share();
    Share(const Share&) = delete;
    Share& operator=(const Share&) = delete;

    // Adds `bytes` to the share, waiting while other jobs hold too much. ResourceExhausted
    // naming the numbers when the share would exceed the whole budget, or when waiting could
    // never end: every job holding a share waits to add to it (their surfaces, say), so none
    // will give memory back; this one then gives up, and its share returns when it is
    // destroyed. Cancelled when `cancel` fires while waiting (looked at every 50 ms).
    absl::Status Add(int64_t bytes, const CancelToken& cancel);

    // Adds `bytes` to the share now when they fit beside the other shares; never waits (for
    // work that a caller can ask for again, a download's conversion). ResourceExhausted naming
    // `what` and the numbers otherwise: over the whole budget, or over what is free now.
    absl::Status TryAdd(int64_t bytes, absl::string_view what);

    int64_t bytes() const { return bytes_; }

   private:
    // Takes `bytes` at once when the budget has no limit (or there is nothing to take), and
    // refuses a share that would exceed the whole budget, naming `what` and `advice`; nullopt
    // when neither applies and the caller reserves them.
    std::optional<absl::Status> Settled(int64_t bytes, absl::string_view what,
                                        absl::string_view advice);

    MemoryBudget& budget_;
    int64_t bytes_ = 0;
  };

  // The whole budget in bytes; <= 0: no limit.
  int64_t total() const { return total_; }
  // The bytes reserved by all shares now (for the metrics).
  int64_t reserved() const ABSL_LOCKS_EXCLUDED(mutex_);
  // The shares waiting in Add now (for the metrics, and for tests to wait on).
  int waiting() const ABSL_LOCKS_EXCLUDED(mutex_);

 private:
  const int64_t total_;
  mutable absl::Mutex mutex_;
  int64_t reserved_ ABSL_GUARDED_BY(mutex_) = 0;
  int holders_ ABSL_GUARDED_BY(mutex_) = 0;          // shares holding bytes
  int waiting_holders_ ABSL_GUARDED_BY(mutex_) = 0;  // of those, the ones waiting in Add
  int waiting_ ABSL_GUARDED_BY(mutex_) = 0;          // shares waiting in Add, holders or not
};

// The budget membraned takes when --memory-budget-bytes is not given: 3/4 of `total_bytes`
// (MachineMemory::total_bytes: the machine's memory, or its container's limit), leaving the
// rest to what the estimates do not count: the uploads' own pool (UploadMemory, 1/8), gRPC's
// buffers, the decoder processes. 0 (no limit) when `total_bytes` is unknown (<= 0).
int64_t DefaultMemoryBudget(int64_t total_bytes);

}  // namespace membrane::server

#endif  // MEMBRANE_SERVER_MEMORY_BUDGET_H_
