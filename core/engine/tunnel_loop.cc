#include "core/engine/tunnel_loop.h"

#include <algorithm>
#include <bit>
#include <iterator>
#include <utility>
#include <vector>

#include "absl/container/flat_hash_set.h"
#include "core/engine/local_topology.h"

namespace membrane {
namespace {

// Grid index of neighbourhood bit `b` around `index`.
int64_t NeighbourIndex(const VoxelGrid& grid, int64_t index, int b) {
  const auto st = grid.strides();
  return index + (b % 3 - 1) * st[0] + ((b / 3) % 3 - 1) * st[1] + (b / 9 - 1) * st[2];
}

std::vector<int64_t> IndicesOf(const VoxelGrid& grid, int64_t index, uint32_t mask) {
  std::vector<int64_t> out;
  for (; mask != 0; mask &= mask - 1) {
    out.push_back(NeighbourIndex(grid, index, std::countr_zero(mask)));
  }
  return out;
}

// The face layer of the block at offset `side` (-1 or +1) along `axis`.
constexpr uint32_t FaceLayer(int axis, int side) {
  uint32_t layer = 0;
  for (int b = 0; b < 27; ++b) {
    const int offset[3] = {b % 3 - 1, (b / 3) % 3 - 1, b / 9 - 1};
    if (offset[axis] == side) layer |= 1u << b;
  }
  return layer;
}

}  // namespace

bool InOneFaceLayer(uint32_t mask) {
  static constexpr uint32_t kLayers[6] = {FaceLayer(0, -1), FaceLayer(0, 1), FaceLayer(1, -1),
                                          FaceLayer(1, 1),  FaceLayer(2, -1), FaceLayer(2, 1)};
  mask &= kAll27 & ~kCentreBit;
  return std::any_of(std::begin(kLayers), std::end(kLayers),
                     [mask](uint32_t layer) { return (mask & ~layer) == 0; });
}

bool SameGenerationAcrossTunnel(const VoxelGrid& grid, int64_t index, uint32_t outside) {
  const auto st = grid.strides();
  const VoxelState* s = grid.states().data() + index;
  const uint32_t rest = outside & N18Mask();
  for (int d = 0; d < 3; ++d) {
    const int off[3] = {d == 0, d == 1, d == 2};
    const uint32_t a = 1u << NeighbourBit(-off[0], -off[1], -off[2]);
    const uint32_t b = 1u << NeighbourBit(off[0], off[1], off[2]);
    if ((rest & a) == 0 || (rest & b) == 0 || (Flood6(a, rest) & b) != 0) continue;
    if (GenerationLabel(s[-st[d]]) == GenerationLabel(s[st[d]])) return true;
  }
  return false;
}

bool TunnelClosesShortLoop(const VoxelGrid& grid, int64_t index, uint32_t outside,
                           int max_steps) {
  // The two components T6 counts: 6-components of the outside face and edge neighbours that
  // hold a face neighbour. Other outside neighbours (lone edge voxels) are no side of the
  // tunnel, so reaching them proves nothing.
  const uint32_t rest = outside & N18Mask();
  const uint32_t faces = rest & FaceNeighboursMask();
  if (faces == 0) return false;
  const uint32_t first = Flood6(faces & (~faces + 1), rest);
  const uint32_t other_faces = faces & ~first;
  if (other_faces == 0) return false;
  const uint32_t second = Flood6(other_faces & (~other_faces + 1), rest);
  if ((faces & ~first & ~second) != 0) return false;  // T6 > 2

  // Breadth-first from the first side, at most max_steps face steps, through outside voxels
  // other than the centre, until a voxel of the second side is reached.
  const auto st = grid.strides();
  const VoxelState* s = grid.states().data();
  const std::vector<int64_t> targets = IndicesOf(grid, index, second);
  std::vector<int64_t> front = IndicesOf(grid, index, first), next;
  absl::flat_hash_set<int64_t> seen(front.begin(), front.end());
  seen.insert(index);
  const int64_t steps[6] = {st[0], -st[0], st[1], -st[1], st[2], -st[2]};
  for (int d = 0; d < max_steps && !front.empty(); ++d) {
    next.clear();
    for (const int64_t v : front) {
      if (grid.OnArrayBorder(grid.CoordOf(v))) continue;
      for (const int64_t step : steps) {
        const int64_t w = v + step;
        if (!IsOutside(s[w]) || !seen.insert(w).second) continue;
        if (std::find(targets.begin(), targets.end(), w) != targets.end()) return true;
        next.push_back(w);
      }
    }
    std::swap(front, next);
  }
  return false;
}

}  // namespace membrane
