// How far a long stage has come: the stage's code counts its work as it goes, and whoever
// shows the stage's progress reads the fraction done from another thread. Passed down the
// stages as the cancel token is; counting never changes what a stage computes.
#ifndef MEMBRANE_CORE_BASE_PROGRESS_METER_H_
#define MEMBRANE_CORE_BASE_PROGRESS_METER_H_

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <mutex>
#include <optional>

namespace membrane {

class ProgressMeter {
 public:
  ProgressMeter() = default;
  ProgressMeter(const ProgressMeter&) = delete;
  ProgressMeter& operator=(const ProgressMeter&) = delete;

  // Begins a step that covers [from, to] of the stage (0 <= from <= to <= 1) and takes `units`
  // units of work: the fraction goes from `from` to `to` as Add counts them. Steps begin in
  // order, each after every Add of the one before it has returned.
  void BeginStep(double from, double to, int64_t units) {
    std::lock_guard<std::mutex> lock(mutex_);
    done_.store(0, std::memory_order_relaxed);
    from_ = from;
    to_ = to;
    units_ = std::max<int64_t>(units, 1);
    begun_ = true;
  }

  // Counts `units` more units of the current step as done. Any thread; a relaxed atomic add,
  // so callers add once per batch of work (a slab, a few thousand cells), not per item.
  void Add(int64_t units) { done_.fetch_add(units, std::memory_order_relaxed); }

  // The fraction of the stage done, in [0, 1]; nullopt before the first step (a stage that
  // does not count its work). Any thread.
  std::optional<double> fraction() const {
    std::lock_guard<std::mutex> lock(mutex_);
    if (!begun_) return std::nullopt;
    const int64_t done = done_.load(std::memory_order_relaxed);
    // Exactly `to` at the step's end, whatever the rounding of the sum below.
    if (done >= units_) return to_;
    return from_ + (to_ - from_) * static_cast<double>(done) / static_cast<double>(units_);
  }

  // Forgets the steps, for the next stage.
  void Reset() {
    std::lock_guard<std::mutex> lock(mutex_);
    done_.store(0, std::memory_order_relaxed);
    begun_ = false;
  }

 private:
  mutable std::mutex mutex_;
  double from_ = 0, to_ = 0;
  int64_t units_ = 1;
  bool begun_ = false;
  std::atomic<int64_t> done_{0};
};

// The part [from, to] of a stage's meter that one function's work covers; the function
// divides it among its own steps (Part, Begin, Add). A default range counts nowhere, for
// callers that show no progress. Small: pass it by value.
class ProgressRange {
 public:
  ProgressRange() = default;
  // All of `meter` (not owned; may be null) from `from` to `to`.
  explicit ProgressRange(ProgressMeter* meter, double from = 0, double to = 1)
      : meter_(meter), from_(from), to_(to) {}

  // The part [a, b] of this range, a and b as fractions of it (0 <= a <= b <= 1).
  ProgressRange Part(double a, double b) const {
    return ProgressRange(meter_, At(a), At(b));
  }
  // Begins this range as one step of `units` units (ProgressMeter::BeginStep).
  void Begin(int64_t units) const {
    if (meter_ != nullptr) meter_->BeginStep(from_, to_, units);
  }
  // Counts `units` more units done (ProgressMeter::Add). Any thread.
  void Add(int64_t units) const {
    if (meter_ != nullptr) meter_->Add(units);
  }
  // Begins this range as one step and ends it: for work that cannot count itself.
  void Done() const {
    Begin(1);
    Add(1);
  }
  // Whether this range counts on a meter: false for a default range, so that work whose
  // counting costs something (a read of /proc) can skip it.
  bool counts() const { return meter_ != nullptr; }

 private:
  double At(double t) const { return t >= 1 ? to_ : from_ + (to_ - from_) * t; }

  ProgressMeter* meter_ = nullptr;
  double from_ = 0, to_ = 1;
};

}  // namespace membrane

#endif  // MEMBRANE_CORE_BASE_PROGRESS_METER_H_
