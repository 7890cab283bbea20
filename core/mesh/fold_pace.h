// The pace at which the caps' folds untangle (HoleCapOptions::untangle_window,
// untangle_fall): each region's crossing pairs, round after round, and whether they have
// stopped falling.
#ifndef MEMBRANE_CORE_MESH_FOLD_PACE_H_
#define MEMBRANE_CORE_MESH_FOLD_PACE_H_

#include <cstdint>
#include <vector>

#include "absl/types/span.h"

namespace membrane {

class FoldPace {
 public:
  // `regions` regions; `window` rounds (0: nothing stalls); `fall` in [0, 1].
  FoldPace(int regions, int window, double fall);

  // Records one round: `pairs[r]` is region r's count of crossing pairs this round (one
  // entry per region). A region's rounds count from the first with pairs.
  void Record(absl::Span<const int64_t> pairs);

  // Whether region r, with pairs at the last recorded round, has stalled: those pairs are
  // more than (1 - fall) times its pairs `window` rounds before (a fold not coming apart).
  // False while the region has fewer than `window` rounds before the last, or none now.
  bool Stalled(int r) const;

 private:
  int window_;
  double fall_;
  std::vector<std::vector<int64_t>> history_;  // per region, from its first round with pairs
};

}  // namespace membrane

#endif  // MEMBRANE_CORE_MESH_FOLD_PACE_H_
