#include "core/mesh/fold_pace.h"

namespace membrane {

FoldPace::FoldPace(int regions, int window, double fall)
    : window_(window), fall_(fall), history_(static_cast<size_t>(regions)) {}

void FoldPace::Record(absl::Span<const int64_t> pairs) {
  for (size_t r = 0; r < history_.size() && r < pairs.size(); ++r)
    if (pairs[r] > 0 || !history_[r].empty()) history_[r].push_back(pairs[r]);
}

bool FoldPace::Stalled(int r) const {
  const std::vector<int64_t>& h = history_[static_cast<size_t>(r)];
  if (window_ <= 0 || h.size() <= static_cast<size_t>(window_) || h.back() == 0) return false;
  const int64_t before = h[h.size() - 1 - static_cast<size_t>(window_)];
  return static_cast<double>(h.back()) > (1.0 - fall_) * static_cast<double>(before);
}

}  // namespace membrane
