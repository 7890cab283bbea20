#include "server/memory_budget.h"

#include <algorithm>

#include "absl/strings/str_format.h"
#include "absl/time/time.h"

namespace membrane::server {

int64_t MemoryBudget::reserved() const {
  absl::MutexLock lock(&mutex_);
  return reserved_;
}

int MemoryBudget::waiting() const {
  absl::MutexLock lock(&mutex_);
  return waiting_;
}

int64_t DefaultMemoryBudget(int64_t total_bytes) {
  return total_bytes > 0 ? total_bytes / 4 * 3 : 0;
}

MemoryBudget::Share::~Share() {
  if (bytes_ == 0 || budget_.total_ <= 0) return;
  absl::MutexLock lock(&budget_.mutex_);
  budget_.reserved_ -= bytes_;
  --budget_.holders_;
}

std::optional<absl::Status> MemoryBudget::Share::Settled(int64_t bytes, absl::string_view what,
                                                         absl::string_view advice) {
  if (budget_.total_ <= 0 || bytes <= 0) {
    bytes_ += std::max<int64_t>(bytes, 0);
    return absl::OkStatus();
  }
  if (bytes_ + bytes > budget_.total_) {
    return absl::ResourceExhaustedError(
        absl::StrFormat("%s needs about %d bytes, over the server's memory budget of %d bytes%s",
                        what, bytes_ + bytes, budget_.total_, advice));
  }
  return std::nullopt;
}

absl::Status MemoryBudget::Share::Add(int64_t bytes, const CancelToken& cancel) {
  if (std::optional<absl::Status> s = Settled(bytes, "the job", "; use a larger voxel_size")) {
    return *s;
  }
  MemoryBudget& b = budget_;
  absl::MutexLock lock(&b.mutex_);
  const bool holder = bytes_ > 0;
  // Every holder waiting means no share will shrink: waiting would never end.
  auto stuck = [&b, holder]() ABSL_EXCLUSIVE_LOCKS_REQUIRED(b.mutex_) {
    return holder && b.waiting_holders_ == b.holders_;
  };
  auto ready = [&b, bytes, &stuck]() ABSL_EXCLUSIVE_LOCKS_REQUIRED(b.mutex_) {
    return b.reserved_ + bytes <= b.total_ || stuck();
  };
  if (holder) ++b.waiting_holders_;
  ++b.waiting_;
  absl::Status status = absl::OkStatus();
  while (!b.mutex_.AwaitWithTimeout(absl::Condition(&ready), absl::Milliseconds(50))) {
    if (cancel.cancelled()) {
      status = absl::CancelledError("cancelled while waiting for memory");
      break;
    }
  }
  if (status.ok() && b.reserved_ + bytes > b.total_) {
    status = absl::ResourceExhaustedError(absl::StrFormat(
        "the job needs %d more bytes while every running job waits for memory the others "
        "hold (%d of %d bytes reserved); retry later, or use a larger voxel_size",
        bytes, b.reserved_, b.total_));
  }
  if (holder) --b.waiting_holders_;
  --b.waiting_;
  if (!status.ok()) return status;
  b.reserved_ += bytes;
  if (!holder) ++b.holders_;
  bytes_ += bytes;
  return absl::OkStatus();
}

absl::Status MemoryBudget::Share::TryAdd(int64_t bytes, absl::string_view what) {
  if (std::optional<absl::Status> s = Settled(bytes, what, " (--memory-budget-bytes)")) {
    return *s;
  }
  MemoryBudget& b = budget_;
  absl::MutexLock lock(&b.mutex_);
  if (b.reserved_ + bytes > b.total_) {
    return absl::ResourceExhaustedError(absl::StrFormat(
        "%s needs about %d bytes while the running jobs hold %d of the server's memory budget "
        "of %d bytes; retry later",
        what, bytes, b.reserved_, b.total_));
  }
  b.reserved_ += bytes;
  if (bytes_ == 0) ++b.holders_;
  bytes_ += bytes;
  return absl::OkStatus();
}

}  // namespace membrane::server
