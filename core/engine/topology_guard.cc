#include "core/engine/topology_guard.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <vector>

#include "core/engine/local_topology.h"
#include "core/engine/tunnel_loop.h"

namespace membrane {
namespace {

// True when removing the voxel would leave one of its local components as a 26-component of at
// most `min_shell_voxels` voxels: each is grown through the grid (without the voxel itself)
// until it is known to be larger.
bool CutsOffSmallComponent(const VoxelGrid& grid, int64_t index, uint32_t outside,
                           int min_shell_voxels) {
  // Each local 26-component of the remaining non-outside neighbours, grown through the grid
  // (without the voxel itself) until it is known to be larger than the limit.
  const std::array<int64_t, 27>& offsets = grid.block_offsets();
  const VoxelState* s = grid.states().data();
  uint32_t rest = ~outside & kAll27 & ~kCentreBit;
  std::vector<int64_t> seen, stack;
  while (rest != 0) {
    const uint32_t seed = rest & (~rest + 1);
    rest &= ~Flood26(seed, rest);
    const int b = std::countr_zero(seed);
    const int64_t start = index + offsets[b];
    seen.assign(1, start);
    stack.assign(1, start);
    while (!stack.empty() && static_cast<int>(seen.size()) <= min_shell_voxels) {
      const int64_t v = stack.back();
      stack.pop_back();
      for (int64_t offset : offsets) {
        const int64_t w = v + offset;
        if (w == index || IsOutside(s[w]) || std::find(seen.begin(), seen.end(), w) != seen.end())
          continue;
        seen.push_back(w);
        stack.push_back(w);
      }
    }
    if (static_cast<int>(seen.size()) <= min_shell_voxels) return true;
  }
  return false;
}

}  // namespace

GuardVerdict ClassifyRemoval(const VoxelGrid& grid, int64_t index, const GuardOptions& options) {
  constexpr GuardVerdict kRefused = GuardVerdict::kRefused, kAllowed = GuardVerdict::kAllowed;
  const GuardSizes& sizes = options.sizes;
  const std::array<int64_t, 27>& offsets = grid.block_offsets();
  const VoxelState* s = grid.states().data() + index;
  uint32_t outside = 0, hard = 0;
  for (int k = 0; k < 27; ++k) {
    const VoxelState n = s[offsets[k]];
    if (IsOutside(n)) outside |= 1u << k;
    if (IsHard(n)) hard |= 1u << k;
  }
  outside &= ~kCentreBit;
  hard &= ~kCentreBit;
  // One outside neighbour, across a face: removing the voxel only dents the membrane.
  if (std::has_single_bit(outside) && (outside & FaceNeighboursMask()) != 0) return kAllowed;
  if (CountT6(outside) == 1) {
    // Simple, or a local split (mitosis). A split that cuts off a few voxels is not mitosis
    // but a stray hard voxel of a sparse region left as a shell of its own.
    return CountT26(~outside & kAll27 & ~kCentreBit) == 1 ||
                   !CutsOffSmallComponent(grid, index, outside, sizes.min_shell_voxels)
               ? kAllowed
               : kRefused;
  }
  // It would open a tunnel. Next to the data (Property 8), only the notch of a soft sheet
  // along a wall: the hard neighbours on one side only (a gap in a wall has them on two), the
  // loop short (a bridge about one voxel thick is cut), and both sides turned outside by the
  // same generation (plates cutting one sheet from both sides; a plate that got through a gap
  // joins a fresh dig to an older outside). Two spheres 2.5-5 voxels apart split this way.
  if (hard != 0) {
    if (sizes.wall_notch_min_plate <= 0 || options.plate_size < sizes.wall_notch_min_plate ||
        !InOneFaceLayer(hard) || !SameGenerationAcrossTunnel(grid, index, outside) ||
        !TunnelClosesShortLoop(grid, index, outside, sizes.short_loop_steps)) {
      return kRefused;
    }
    const bool strict_notch = options.strict.wall_notch_min_plate > 0 &&
                              options.plate_size >= options.strict.wall_notch_min_plate;
    return !options.classify_strict || strict_notch ? kAllowed : GuardVerdict::kAllowedLoosely;
  }
  const int n = options.plate_size;
  // The short-loop test walks the outside: run at most once, and only where it decides.
  auto short_loop = [&, known = false, value = false]() mutable {
    if (!known) value = TunnelClosesShortLoop(grid, index, outside, sizes.short_loop_steps);
    known = true;
    return value;
  };
  auto strict_allows = [&] {
    return n >= options.strict.tunnel_min_plate ||
           (options.strict.short_loop_min_plate > 0 && n >= options.strict.short_loop_min_plate &&
            short_loop());
  };
  // Away from the data, a big plate may open any tunnel: one large for the object, or one
  // with data all around it, a real hole's rim and not a gap between sparse samples (both grow
  // with the grid, the samples' spacing in voxels does not)...
  const auto dense_rim = [&] {
    return HardVoxelsWithin(grid, grid.CoordOf(index), n,
                            static_cast<int64_t>(std::ceil(sizes.dense_rim * n * n)));
  };
  if (n >= sizes.tunnel_min_plate && (n >= sizes.object_tunnel_plate || dense_rim())) {
    return !options.classify_strict || strict_allows() ? kAllowed : GuardVerdict::kAllowedLoosely;
  }
  // ...or where the loop it closes through the outside is short: it then notches a soft bridge
  // about one voxel thick, the first cut of the split of a sheet between two shells (two
  // spheres 5-10 voxels apart), which a plate too small for the guard's tunnels must make.
  // A hole through a wall closes a long loop, around the wall. Measured in engine-decisions.md.
  if (sizes.short_loop_min_plate <= 0 || n < sizes.short_loop_min_plate || !short_loop())
    return kRefused;
  return !options.classify_strict || strict_allows() ? kAllowed : GuardVerdict::kAllowedLoosely;
}

}  // namespace membrane
