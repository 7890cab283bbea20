// The bytes of uploads membraned holds at once (--upload-memory-bytes): an upload is held from
// its header until its job's decoding ends (while it arrives, waits in the queue and is fed to
// the decoder), outside the jobs' memory budget. Without this, a full queue of uploads at
// --max-upload-bytes (16 x 512 MB) could hold more memory than the machine has.
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
    Hold(UploadMemory* owner, int64_t bytes) : owner_(owner), bytes_(bytes) {}
    UploadMemory* owner_ = nullptr;
    int64_t bytes_ = 0;
  };

  // A hold of `bytes` when they fit beside the uploads held now, never waiting.
  // ResourceExhausted naming the bytes and the limit otherwise: "over the server's memory for
  // uploads" when they never fit (!Fits), "the server is busy" when they would once others are
  // released (worth retrying).
  absl::StatusOr<Hold> Reserve(int64_t bytes) ABSL_LOCKS_EXCLUDED(mutex_);

  // True when `bytes` fit within the limit at all.
  bool Fits(int64_t bytes) const { return total_ <= 0 || bytes <= total_; }

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
