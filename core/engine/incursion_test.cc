#include "core/engine/incursion_test.h"

#include <cstdlib>  // std::abs
#include <vector>

#include "core/engine/local_topology.h"
#include "core/engine/thin_wall_faces.h"

namespace membrane {
namespace {

// 6-flood inside a box of 3 x 3 x len voxels (len <= 7) held in a uint64 mask:
// bit t * 9 + i * 3 + j, t along the tested axis, (i, j) across it.
uint64_t FloodBox(uint64_t seed, uint64_t allowed, int len) {
  uint64_t not_j2 = 0, not_j0 = 0, not_i2 = 0, not_i0 = 0;
  for (int b = 0; b < 9 * len; ++b) {
    const int j = b % 3, i = (b / 3) % 3;
    if (j != 2) not_j2 |= 1ull << b;
    if (j != 0) not_j0 |= 1ull << b;
    if (i != 2) not_i2 |= 1ull << b;
    if (i != 0) not_i0 |= 1ull << b;
  }
  uint64_t reach = seed & allowed;
  for (;;) {
    uint64_t next = reach | ((reach & not_j2) << 1) | ((reach & not_j0) >> 1) |
                    ((reach & not_i2) << 3) | ((reach & not_i0) >> 3) | (reach << 9) |
                    (reach >> 9);
    next &= allowed;
    if (next == reach) return reach;
    reach = next;
  }
}

// Whether the outside voxels a and b are joined by a 6-path of outside voxels inside the cube
// of radius r (Chebyshev) around `centre`: a breadth-first search over at most (2r + 1)^3
// voxels.
bool JoinedInCube(const VoxelGrid& grid, int64_t centre, int64_t a, int64_t b, int r) {
  const Coord c = grid.CoordOf(centre);
  static constexpr int kSteps[6][3] = {{1, 0, 0},  {-1, 0, 0}, {0, 1, 0},
                                       {0, -1, 0}, {0, 0, 1},  {0, 0, -1}};
  const int side = 2 * r + 1;
  std::vector<uint8_t> seen(static_cast<size_t>(side) * side * side, 0);
  std::vector<Coord> queue;
  auto local = [&](const Coord& q) {
    return (q.x - c.x + r) + side * ((q.y - c.y + r) + side * (q.z - c.z + r));
  };
  const Coord ca = grid.CoordOf(a), cb = grid.CoordOf(b);
  auto in_cube = [&](const Coord& q) {
    return std::abs(q.x - c.x) <= r && std::abs(q.y - c.y) <= r && std::abs(q.z - c.z) <= r;
  };
  if (!in_cube(ca) || !in_cube(cb)) return false;
  queue.push_back(ca);
  seen[local(ca)] = 1;
  const VoxelState* s = grid.states().data();
  for (size_t h = 0; h < queue.size(); ++h) {
    const Coord q = queue[h];
    if (q.x == cb.x && q.y == cb.y && q.z == cb.z) return true;
    for (const auto& e : kSteps) {
      const Coord n{q.x + e[0], q.y + e[1], q.z + e[2]};
      if (!in_cube(n) || !grid.Contains(n)) continue;
      const int l = local(n);
      if (seen[l] || !IsOutside(s[grid.Index(n)])) continue;
      seen[l] = 1;
      queue.push_back(n);
    }
  }
  return false;
}

// Whether the points around the run [lo, hi] along axis d through `index` (one voxel either
// side across it) show data on both of its sides (ThinPartRule::min_spread).
bool ThinPartData(const VoxelGrid& grid, int64_t index, int d, int lo, int hi,
                  const ThinPartRule& thin) {
  if (thin.min_spread <= 0) return true;
  if (thin.points == nullptr) return false;
  const Coord c = grid.CoordOf(index);
  Coord a = c, b = c;
  for (int k = 0; k < 3; ++k) {
    a[k] = k == d ? c[k] + lo : c[k] - 1;
    b[k] = k == d ? c[k] + hi : c[k] + 1;
  }
  return thin.points->PlaneSpread(grid, a, b) >= thin.min_spread;
}

// Whether the outside voxels a and b at the two ends of a run face the two faces of a thin
// wall (ThinPartRule::min_face_gap; FacingGap).
bool FacesOfAThinWall(const VoxelGrid& grid, int64_t a, int64_t b, const ThinPartRule& thin) {
  return thin.min_face_gap > 0 && thin.points != nullptr &&
         FacingGap(grid, *thin.points, grid.CoordOf(a), grid.CoordOf(b)) >= thin.min_face_gap;
}

}  // namespace

bool OutsideJoinedInCube(const VoxelGrid& grid, int64_t centre, int64_t a, int64_t b, int r) {
  return JoinedInCube(grid, centre, a, b, r);
}

bool PaperIncursion(const VoxelGrid& grid, int64_t index, const ThinPartRule& thin) {
  const auto st = grid.strides();
  const VoxelState* s = grid.states().data() + index;
  uint32_t outside = 0;
  bool computed = false;
  for (int d = 0; d < 3; ++d) {
    const VoxelState a = s[-st[d]], b = s[st[d]];
    if (!IsOutside(a) || !IsOutside(b) || GenerationLabel(a) == GenerationLabel(b)) continue;
    if (!computed) {
      outside = OutsideMask(grid, index) & ~kCentreBit;
      computed = true;
    }
    const int off[3] = {d == 0, d == 1, d == 2};
    const uint32_t bit_a = 1u << NeighbourBit(-off[0], -off[1], -off[2]);
    const uint32_t bit_b = 1u << NeighbourBit(off[0], off[1], off[2]);
    if ((Flood6(bit_a, outside) & bit_b) != 0) continue;
    // A wall of one voxel with data on both of its faces: a thin part, as a thick-wall run's.
    if (thin.face_max_run >= 1 && FacesOfAThinWall(grid, index - st[d], index + st[d], thin))
      continue;
    return true;
  }
  return false;
}

bool ThickWallIncursion(const VoxelGrid& grid, int64_t index, int max_run,
                         const ThinPartRule& thin) {
  const auto st = grid.strides();
  const VoxelState* s = grid.states().data();
  for (int d = 0; d < 3; ++d) {
    const int64_t sd = st[d];
    int lo = 0, hi = 0;
    while (hi - lo + 1 < max_run && IsHardOrFrozen(s[index + (hi + 1) * sd])) ++hi;
    while (hi - lo + 1 < max_run && IsHardOrFrozen(s[index + (lo - 1) * sd])) --lo;
    if (hi == lo) continue;
    const VoxelState a = s[index + (lo - 1) * sd], b = s[index + (hi + 1) * sd];
    if (!IsOutside(a) || !IsOutside(b) || GenerationLabel(a) == GenerationLabel(b)) continue;
    // Outside voxels of the box A..B along d, -1..1 across it.
    const int d1 = (d + 1) % 3, d2 = (d + 2) % 3;
    const int len = hi - lo + 3;
    uint64_t outside = 0;
    for (int t = 0; t < len; ++t)
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
          const int64_t at = index + (lo - 1 + t) * sd + (i - 1) * st[d1] + (j - 1) * st[d2];
          if (IsOutside(s[at])) outside |= 1ull << (t * 9 + i * 3 + j);
        }
    const uint64_t bit_a = 1ull << 4, bit_b = 1ull << ((len - 1) * 9 + 4);
    if ((FloodBox(bit_a, outside, len) & bit_b) != 0) continue;
    // Joined around the run a little further out, with data on both of its sides: a thin
    // part (a leg, a horn, a belt), both of whose sides are the exterior, not a wall with a
    // dig behind it. The points are read first: they are cheaper than the search.
    if (thin.detour > 0 && ThinPartData(grid, index, d, lo, hi, thin) &&
        JoinedInCube(grid, index, index + (lo - 1) * sd, index + (hi + 1) * sd, thin.detour)) {
      continue;
    }
    // Data on both faces of a wall, seen from its two ends: the two sides of a thin wall,
    // however far around they meet.
    if (hi - lo + 1 <= thin.face_max_run &&
        FacesOfAThinWall(grid, index + (lo - 1) * sd, index + (hi + 1) * sd, thin)) {
      continue;
    }
    return true;
  }
  return false;
}

}  // namespace membrane
