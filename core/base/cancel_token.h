// Cooperative cancellation shared between a caller and a running reconstruction: the one way
// every stage (decode, engine, mesh steps, admission waits) is asked to stop.
#ifndef MEMBRANE_CORE_BASE_CANCEL_TOKEN_H_
#define MEMBRANE_CORE_BASE_CANCEL_TOKEN_H_

#include <atomic>

namespace membrane {

// Set from any thread; the stages poll it between units of work (contractions, the word
// passes of a snapshot, relaxation steps, slabs of the fit), so a cancel returns within
// milliseconds. Passed as `const CancelToken&`; a caller that never cancels passes
// CancelToken::Never(). It fills a cache line of its own: the stages poll it millions of
// times, and a token sharing its line with fields another thread writes (a job's progress,
// its mutex) would make every poll a cache miss.
class alignas(64) CancelToken {
 public:
  CancelToken() = default;
  CancelToken(const CancelToken&) = delete;
  CancelToken& operator=(const CancelToken&) = delete;

  // A token that is never cancelled (it is const: nobody can call Cancel on it).
  static const CancelToken& Never() {
    static const CancelToken never;
    return never;
  }

  void Cancel() { cancelled_.store(true, std::memory_order_relaxed); }
  bool cancelled() const { return cancelled_.load(std::memory_order_relaxed); }

 private:
  std::atomic<bool> cancelled_{false};
};

}  // namespace membrane

#endif  // MEMBRANE_CORE_BASE_CANCEL_TOKEN_H_
