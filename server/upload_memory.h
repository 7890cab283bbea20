// The bytes of uploads membraned holds at once (--upload-memory-bytes): an upload holds its
// buffer's bytes from its first chunk until its job's decoding ends (while it arrives, waits
// in the queue and is fed to the decoder), outside the jobs' memory budget. Without this, a
// full queue of uploads at --max-upload-bytes (16 x 512 MB) could hold more memory than the
// machine has.
#ifndef MEMBRANE_SERVER_UPLOAD_MEMORY_H_
#define MEMBRANE_SERVER_UPLOAD_MEMORY_H_

#include <cstdint>

#include "absl/base/thread_annotations.h"
#include "absl/status/statusor.h"
#include "absl/synchronization/mutex.h"

namespace membrane::server {

class UploadMemory {
 public:
  // `total_bytes` <= 0: no limit.
  explicit UploadMemory(int64_t total_bytes) : total_(total_bytes) {}

  // One upload's bytes, given back when released or destroyed. Must not outlive the
  // UploadMemory it came from.
  class Hold {
   public:
    Hold() = default;
    Hold(Hold&& other) noexcept;
    Hold& operator=(Hold&& other) noexcept;
    ~Hold() { Release(); }
    // Gives the bytes back (again: nothing).
    void Release();
    int64_t bytes() const { return bytes_; }

   private:
    friend class UploadMemory;
    UploadMemory* owner_ = nullptr;
    int64_t bytes_ = 0;
  };

  // OK when an upload of `bytes` fits within the limit at all; ResourceExhausted "over the
  // server's memory for uploads", naming both, when it never will (not worth retrying).
  absl::Status CheckFits(int64_t bytes) const;

  // Adds `bytes` to `hold` (an empty hold becomes one of this UploadMemory) when they fit
  // beside the uploads held now, never waiting; else ResourceExhausted "the server is busy"
  // naming the numbers (worth retrying once others are released), and `hold` is unchanged.
  // An upload grows its hold with its buffer, so a call that announces much and sends little
  // holds little.
  absl::Status Grow(Hold& hold, int64_t bytes) ABSL_LOCKS_EXCLUDED(mutex_);

  int64_t held() const ABSL_LOCKS_EXCLUDED(mutex_);

 private:
  void Give(int64_t bytes) ABSL_LOCKS_EXCLUDED(mutex_);

  const int64_t total_;
  mutable absl::Mutex mutex_;
  int64_t held_ ABSL_GUARDED_BY(mutex_) = 0;
};

// The limit membraned takes when --upload-memory-bytes is not given: 1/8 of `total_bytes` (the
// machine's memory or its container's limit; the jobs' budget takes 3/4 of it). 0 (no limit)
// when `total_bytes` is unknown (<= 0).
int64_t DefaultUploadMemory(int64_t total_bytes);

}  // namespace membrane::server

#endif  // MEMBRANE_SERVER_UPLOAD_MEMORY_H_
