// Cooperative cancellation shared between a caller and a running reconstruction.
#ifndef MEMBRANE_CORE_ENGINE_CANCEL_TOKEN_H_
#define MEMBRANE_CORE_ENGINE_CANCEL_TOKEN_H_

#include <atomic>

namespace membrane {

// Set from any thread; the engine polls it between contractions and between the word passes
// of a snapshot, so a cancel returns within milliseconds. It fills a cache line of its own:
// the stages poll it millions of times, and a token sharing its line with fields another
// thread writes (a job's progress, its mutex) would make every poll a cache miss.
class alignas(64) CancelToken {
 public:
  void Cancel() { cancelled_.store(true, std::memory_order_relaxed); }
  bool cancelled() const { return cancelled_.load(std::memory_order_relaxed); }

 private:
  std::atomic<bool> cancelled_{false};
};

}  // namespace membrane

#endif  // MEMBRANE_CORE_ENGINE_CANCEL_TOKEN_H_
