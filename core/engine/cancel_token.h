// Cooperative cancellation shared between a caller and a running reconstruction.
#ifndef MEMBRANE_CORE_ENGINE_CANCEL_TOKEN_H_
#define MEMBRANE_CORE_ENGINE_CANCEL_TOKEN_H_

#include <atomic>

namespace membrane {

// Set from any thread; the engine polls it between contractions and between the word passes
// of a snapshot, so a cancel returns within milliseconds.
class CancelToken {
 public:
  void Cancel() { cancelled_.store(true, std::memory_order_relaxed); }
  bool cancelled() const { return cancelled_.load(std::memory_order_relaxed); }

 private:
  std::atomic<bool> cancelled_{false};
};

}  // namespace membrane

#endif  // MEMBRANE_CORE_ENGINE_CANCEL_TOKEN_H_
