// The first candidate of an ordered scan that fails a read-only test, found on several threads
// with the one-thread scan's answer: which candidate, and how many were tested up to it.
//
// A closed-form generation checks up to millions of voxels (the incursion test, then the
// topology guard) and stops at the first refusal; the tests only read the grid, so spans of
// the candidates can be tested side by side. The statistics count the tests the scan in order
// makes, so the count is rebuilt from the spans: all of those before the first failing span,
// and that span's up to its failure.
#ifndef MEMBRANE_CORE_ENGINE_FIRST_FAILURE_H_
#define MEMBRANE_CORE_ENGINE_FIRST_FAILURE_H_

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <limits>
#include <vector>

#include "core/base/cancel_token.h"
#include "core/base/parallel_tasks.h"

namespace membrane {

struct FirstFailure {
  int64_t tested = 0;      // tests the one-thread scan runs, the failing one included
  bool failed = false;     // some candidate failed
  bool cancelled = false;  // `cancel` fired: the other fields are partial
};

// Scans `spans` spans in order; for_each_in_span(span, visit) calls visit(i) for the span's
// candidates in scan order and stops when visit returns false. fails(i) is the test (it must
// only read shared state: it runs on `threads` threads at once). A span after one that has
// failed stops early. `cancel` is polled every 4096 tests of a worker. With threads <= 1 or
// one span, the spans run in order on the calling thread.
template <typename ForEachInSpan, typename Fails>
FirstFailure FindFirstFailure(int64_t spans, int threads, const CancelToken& cancel,
                              ForEachInSpan for_each_in_span, Fails fails) {
  struct Span {
    int64_t tested = 0;
    bool failed = false;
  };
  std::vector<Span> results(static_cast<size_t>(std::max<int64_t>(spans, 0)));
  std::atomic<int64_t> first_failed{std::numeric_limits<int64_t>::max()};
  TaskCancel task_cancel(cancel, threads, 4096);
  RunTasks(threads, spans, [&](int worker, int64_t span) {
    if (span > first_failed.load(std::memory_order_relaxed) || task_cancel.fired()) return;
    Span& r = results[static_cast<size_t>(span)];
    for_each_in_span(span, [&](int64_t i) {
      if (task_cancel.Poll(worker) || span > first_failed.load(std::memory_order_relaxed)) {
        return false;
      }
      ++r.tested;
      if (!fails(i)) return true;
      r.failed = true;
      int64_t seen = first_failed.load(std::memory_order_relaxed);
      while (span < seen && !first_failed.compare_exchange_weak(seen, span)) {
      }
      return false;
    });
  });
  FirstFailure out;
  if (task_cancel.fired()) {
    out.cancelled = true;
    return out;
  }
  // Every span before the first failing one ran to its end: none of them failed.
  for (const Span& r : results) {
    out.tested += r.tested;
    if (r.failed) {
      out.failed = true;
      break;
    }
  }
  return out;
}

}  // namespace membrane

#endif  // MEMBRANE_CORE_ENGINE_FIRST_FAILURE_H_
