#include "core/pipeline/membrane_counts.h"

#include <utility>

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

}  // namespace

MembraneCounts CountMembrane(const VoxelGrid& grid) {
  MembraneCounts counts;
  // Eight states a word: a membrane's grid is long runs of outside voxels and of soft inside
  // ones (kInsideSoft is 0), each word of which is counted in one test; the words with
  // anything else (the membrane and the hard data) are counted a state at a time.
  constexpr uint64_t kAllOutside = kLowBits8 * kOutsideBit;
  const VoxelState* const s = grid.states().data();
  const int64_t n = grid.size();
  int64_t i = 0;
  for (; i + 8 <= n; i += 8) {
    const uint64_t w = LoadStates8(s + i);
    if ((w & kAllOutside) == kAllOutside) continue;
    if (w == 0) {
      counts.inside_soft_voxels += 8;
      continue;
    }
    for (int k = 0; k < 8; ++k) CountState(s[i + k], counts);
  }
  for (; i < n; ++i) CountState(s[i], counts);
  VoxelTopology topology = ComputeVoxelTopology(grid);
  counts.shells = topology.shells;
  counts.genus = std::move(topology.genus);
  return counts;
}

}  // namespace membrane
