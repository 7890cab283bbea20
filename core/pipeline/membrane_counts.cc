#include "core/pipeline/membrane_counts.h"

#include <cstdint>
#include <utility>
#include <vector>

#include "core/base/parallel_tasks.h"
#include "core/engine/voxel_state.h"
#include "core/engine/voxel_state_words.h"
#include "core/engine/voxel_topology.h"

namespace membrane {
namespace {

void CountState(VoxelState s, MembraneCounts& counts) {
  if (IsOutside(s)) return;
  const bool boundary = IsBoundary(s);
  if (IsHard(s)) {
    ++(boundary ? counts.hard_voxels : counts.inside_hard_voxels);
  } else if (IsFrozen(s)) {
    ++(boundary ? counts.frozen_voxels : counts.inside_frozen_voxels);
  } else {
    ++(boundary ? counts.soft_voxels : counts.inside_soft_voxels);
  }
}

// The states of voxels [begin, end) of `s` added to `counts`. Eight states a word: a
// membrane's grid is long runs of outside voxels and of soft inside ones (kInsideSoft is 0),
// each word of which is counted in one test; the words with anything else (the membrane and
// the hard data) are counted a state at a time.
void CountStates(const VoxelState* s, int64_t begin, int64_t end, MembraneCounts& counts) {
  constexpr uint64_t kAllOutside = kLowBits8 * kOutsideBit;
  int64_t i = begin;
  for (; i + 8 <= end; i += 8) {
    const uint64_t w = LoadStates8(s + i);
    if ((w & kAllOutside) == kAllOutside) continue;
    if (w == 0) {
      counts.inside_soft_voxels += 8;
      continue;
    }
    for (int k = 0; k < 8; ++k) CountState(s[i + k], counts);
  }
  for (; i < end; ++i) CountState(s[i], counts);
}

}  // namespace

MembraneCounts CountMembrane(const VoxelGrid& grid, int threads) {
  // Ranges of the grid a task, each counted on its own and summed: sums of counts, the same
  // for any split.
  const TaskRanges ranges =
      TaskRanges::Split(grid.size(), threads, /*per_thread=*/4, kMinSplitGridVoxels);
  std::vector<MembraneCounts> parts(static_cast<size_t>(ranges.tasks));
  const VoxelState* const s = grid.states().data();
  RunTasks(threads, ranges.tasks, [&](int, int64_t t) {
    CountStates(s, ranges.begin(t), ranges.end(t), parts[static_cast<size_t>(t)]);
  });
  MembraneCounts counts;
  for (const MembraneCounts& part : parts) {
    counts.hard_voxels += part.hard_voxels;
    counts.frozen_voxels += part.frozen_voxels;
    counts.soft_voxels += part.soft_voxels;
    counts.inside_hard_voxels += part.inside_hard_voxels;
    counts.inside_soft_voxels += part.inside_soft_voxels;
    counts.inside_frozen_voxels += part.inside_frozen_voxels;
  }
  VoxelTopology topology = *ComputeVoxelTopology(grid, CancelToken::Never(), threads);
  counts.shells = topology.shells;
  counts.genus = std::move(topology.genus);
  return counts;
}

}  // namespace membrane
