#include "core/engine/interior_guard.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cstring>
#include <vector>

#include "absl/status/status.h"
#include "core/base/parallel_tasks.h"
#include "core/engine/flat_bitset.h"
#include "core/engine/gap_refill.h"
#include "core/engine/membrane_shrinker.h"
#include "core/engine/shrink_options.h"
#include "core/engine/state_planes.h"
#include "core/engine/voxelization.h"

namespace membrane {
namespace {

constexpr int kPad = VoxelGrid::kPadding;

// Marks of a grid's voxels, one byte each.
using Marks = std::vector<uint8_t>;

// For every voxel, how many of its 6 axis rays reach an outside voxel before a hard one (the
// array border counts as outside): 0 to 6.
Marks OpenRays(const VoxelGrid& grid) {
  const std::array<int, 3>& dims = grid.dims();
  const std::array<int64_t, 3> strides = grid.strides();
  Marks open(grid.size(), 0);
  for (int axis = 0; axis < 3; ++axis) {
    const int a1 = axis == 0 ? 1 : 0, a2 = axis == 2 ? 1 : 2;
    const int n = dims[axis];
    for (int j = 0; j < dims[a2]; ++j) {
      for (int i = 0; i < dims[a1]; ++i) {
        const int64_t base = i * strides[a1] + j * strides[a2];
        // Walking against the ray, `open_ahead` is what the ray from the voxel meets first.
        for (int sign = 0; sign < 2; ++sign) {
          bool open_ahead = true;
          for (int t = 0; t < n; ++t) {
            const int64_t v = base + (sign == 0 ? n - 1 - t : t) * strides[axis];
            open[v] += open_ahead;
            const VoxelState s = grid.at(v);
            if (IsHard(s)) open_ahead = false;
            else if (IsOutside(s)) open_ahead = true;
          }
        }
      }
    }
  }
  return open;
}

// The grid `k` times coarser over the same data region, as Voxelize() leaves a grid: padding
// outside, the data region inside with its outer layer boundary, a voxel hard when any of its
// fine voxels is.
VoxelGrid CoarseGrid(const VoxelGrid& fine, int k) {
  std::array<int, 3> dims;
  std::array<double, 3> origin;
  const double l = fine.voxel_size();
  for (int d = 0; d < 3; ++d) {
    dims[d] = (fine.dim(d) - 2 * kPad + k - 1) / k + 2 * kPad;
    origin[d] = fine.origin()[d] + kPad * l - kPad * k * l;
  }
  VoxelGrid coarse(dims, origin, k * l, VoxelGrid::Unset{});
  for (int z = 0; z < dims[2]; ++z) WriteInitialPlane(z, coarse);
  // Before the first generation a data voxel's state has bit 1 set exactly when it is hard:
  // eight voxels at a time are skipped when none has.
  constexpr uint64_t kHardBits = 0x0202020202020202ull;
  const int64_t row = fine.dim(0) - 2 * kPad;
  for (int z = kPad; z < fine.dim(2) - kPad; ++z) {
    for (int y = kPad; y < fine.dim(1) - kPad; ++y) {
      const VoxelState* states = fine.states().data() + fine.Index(kPad, y, z);
      for (int64_t x = 0; x < row; x += 8) {
        if (x + 8 <= row) {
          uint64_t word;
          std::memcpy(&word, states + x, 8);
          if ((word & kHardBits) == 0) continue;
        }
        for (int64_t i = x; i < std::min(row, x + 8); ++i) {
          if (!IsHard(states[i])) continue;
          const int64_t c = coarse.Index(static_cast<int>(i / k) + kPad, (y - kPad) / k + kPad,
                                         (z - kPad) / k + kPad);
          coarse.set(c, IsBoundary(coarse.at(c)) ? kBoundaryHard : kInsideHard);
        }
      }
    }
  }
  return coarse;
}

// The class of a coarse voxel after the coarse shrink and refill.
enum CoarseClass : uint8_t {
  kCoarseOutside = 0,  // outside the coarse membrane
  kCoarseBand = 1,     // in the coarse solid, the rest
  kCoarseCore = 2,     // in the coarse solid, no hard voxel in its 3x3x3 block, at most
                       // max_open_rays axis rays reaching the outside
};

// The fine data-region voxels and their coarse voxels: fine (x, y, z) lies in coarse
// ((x - p) / k + p, ...).
class FineToCoarse {
 public:
  FineToCoarse(const VoxelGrid& fine, const VoxelGrid& coarse, int k)
      : fine_(fine), coarse_(coarse), k_(k) {}
  int64_t Coarse(const Coord& f) const {
    return coarse_.Index((f.x - kPad) / k_ + kPad, (f.y - kPad) / k_ + kPad,
                         (f.z - kPad) / k_ + kPad);
  }
  bool InData(const Coord& f) const {
    for (int d = 0; d < 3; ++d)
      if (f[d] < kPad || f[d] >= fine_.dim(d) - kPad) return false;
    return true;
  }

 private:
  const VoxelGrid& fine_;
  const VoxelGrid& coarse_;
  int k_;
};

constexpr std::array<Coord, 6> kFaceSteps = {Coord{1, 0, 0}, Coord{-1, 0, 0}, Coord{0, 1, 0},
                                             Coord{0, -1, 0}, Coord{0, 0, 1}, Coord{0, 0, -1}};

// Calls visit(fine coord) for every fine voxel of the data region in coarse voxel (cx, cy, cz).
template <typename Visit>
void ForFineOf(const VoxelGrid& fine, int k, int cx, int cy, int cz, Visit visit) {
  const int x0 = kPad + (cx - kPad) * k, y0 = kPad + (cy - kPad) * k, z0 = kPad + (cz - kPad) * k;
  for (int z = z0; z < std::min(z0 + k, fine.dim(2) - kPad); ++z)
    for (int y = y0; y < std::min(y0 + k, fine.dim(1) - kPad); ++y)
      for (int x = x0; x < std::min(x0 + k, fine.dim(0) - kPad); ++x) visit(Coord{x, y, z});
}

}  // namespace

absl::StatusOr<InteriorGuardStats> GuardInteriors(VoxelGrid& grid, const ShrinkOptions& options,
                                                  const CancelToken& cancel, GuardedBand* band) {
  const auto start = std::chrono::steady_clock::now();
  InteriorGuardStats stats;
  const InteriorGuardOptions& o = options.interior_guard;
  if (!o.enabled) return stats;
  const int k = o.factor;
  int longest = 0;
  for (int d = 0; d < 3; ++d) longest = std::max(longest, (grid.dim(d) - 2 * kPad + k - 1) / k);
  if (longest < o.min_coarse_axis) return stats;
  const auto cancelled = [] {
    return absl::CancelledError("reconstruction cancelled while guarding interiors");
  };

  // The coarse membrane, refilled where it carved through data gaps; no dents (they would cut
  // paths into the solid that the fine membrane has no reason to follow).
  VoxelGrid coarse = CoarseGrid(grid, k);
  ShrinkOptions coarse_options = options;
  coarse_options.connect_inside_hard = false;
  absl::StatusOr<ShrinkResult> shrunk = ShrinkMembrane(coarse, {}, coarse_options, {}, cancel);
  if (!shrunk.ok()) return shrunk.status();
  stats.levels = 1 + shrunk->interior_guard.levels;

  // Hard voxels and their 26 neighbours (the padding keeps every hard voxel off the array
  // border, so the dilation does not wrap).
  FlatBitset near_hard(coarse.size()), scratch(coarse.size());
  FillStatePlane(coarse.states(), StatePredicate::kHard, near_hard);
  {
    const std::array<int64_t, 3> st = coarse.strides();
    const int64_t strides[3] = {st[0], st[1], st[2]};
    near_hard.Dilate26(strides, scratch);
  }
  const Marks open_rays = OpenRays(coarse);
  Marks classes(coarse.size());
  for (int64_t i = 0; i < coarse.size(); ++i) {
    const VoxelState c = coarse.at(i);
    if (IsOutside(c)) {
      classes[i] = kCoarseOutside;
    } else if (near_hard.test(i) || open_rays[i] > o.max_open_rays) {
      classes[i] = kCoarseBand;
    } else {
      classes[i] = kCoarseCore;
    }
    stats.core_voxels += classes[i] == kCoarseCore;
  }
  if (stats.core_voxels == 0) return stats;

  const std::array<int, 3>& cd = coarse.dims();
  const auto for_data_coarse = [&](auto visit) {
    for (int cz = kPad; cz < cd[2] - kPad; ++cz)
      for (int cy = kPad; cy < cd[1] - kPad; ++cy)
        for (int cx = kPad; cx < cd[0] - kPad; ++cx) visit(cx, cy, cz);
  };
  // The core: every fine voxel of it is frozen.
  for_data_coarse([&](int cx, int cy, int cz) {
    if (classes[coarse.Index(cx, cy, cz)] != kCoarseCore) return;
    ForFineOf(grid, k, cx, cy, cz, [&](const Coord& f) {
      const int64_t i = grid.Index(f);
      if (grid.at(i) != kInsideSoft) return;
      grid.set(i, kInsideFrozen);
      ++stats.frozen_voxels;
    });
  });
  if (cancel.cancelled()) return cancelled();

  // The band between the core and the coarse outside holds the skin's data. Its fine soft
  // voxels are split by which side reaches them first through soft voxels: two breadth-first
  // waves, from the coarse outside and from the core, the outside's first at each distance
  // (a tie stays soft). The core's wave stops at the skin's data from inside and meets the
  // outside's in the skin's pores; its voxels are frozen.
  const FineToCoarse map(grid, coarse, k);
  // The band's fine voxels, and those either wave has reached, one bit each over the grid.
  FlatBitset band_cells(grid.size()), seen(grid.size());
  for_data_coarse([&](int cx, int cy, int cz) {
    if (classes[coarse.Index(cx, cy, cz)] != kCoarseBand) return;
    ForFineOf(grid, k, cx, cy, cz, [&](const Coord& f) { band_cells.set(grid.Index(f)); });
  });
  // The padding is never band: every face neighbour of a band voxel lies in the array.
  const auto passable = [&](int64_t i) {
    return band_cells.test(i) && grid.at(i) == kInsideSoft;
  };
  // The core's wave stays a voxel off the data: the fine membrane keeps the skin's pores and
  // its inner face as it would find them without the guard.
  const auto near_data = [&](int64_t i) {
    for (int64_t off : grid.neighbour_offsets())
      if (IsHard(grid.at(i + off))) return true;
    return false;
  };
  const auto mark = [&](int64_t i) {
    if (seen.test(i)) return false;
    seen.set(i);
    return true;
  };
  const std::array<int64_t, 3> st = grid.strides();
  const std::array<int64_t, 6> faces = {st[0], -st[0], st[1], -st[1], st[2], -st[2]};
  std::vector<int64_t> outside_front, core_front, next;
  for_data_coarse([&](int cx, int cy, int cz) {
    if (classes[coarse.Index(cx, cy, cz)] != kCoarseBand) return;
    bool touches = false;  // a face neighbour outside or in the core
    for (const Coord& d : kFaceSteps)
      touches = touches || classes[coarse.Index(cx + d.x, cy + d.y, cz + d.z)] != kCoarseBand;
    if (!touches) return;
    ForFineOf(grid, k, cx, cy, cz, [&](const Coord& f) {
      if (grid.at(f) != kInsideSoft) return;
      bool out = false, core = false;
      for (const Coord& d : kFaceSteps) {
        const Coord g{f.x + d.x, f.y + d.y, f.z + d.z};
        if (!map.InData(g) || grid.at(g) == kBoundarySoft) {
          out = true;
          continue;
        }
        out = out || classes[map.Coarse(g)] == kCoarseOutside;
        core = core || grid.at(g) == kInsideFrozen;
      }
      const int64_t i = grid.Index(f);
      if (out) {
        mark(i);
        outside_front.push_back(i);
      } else if (core) {
        core_front.push_back(i);
      }
    });
  });
  // Core seeds a face away from the outside too are the outside's (marked above).
  next.clear();
  for (int64_t i : core_front) {
    if (near_data(i) || !mark(i)) continue;
    grid.set(i, kInsideFrozen);
    ++stats.band_frozen;
    next.push_back(i);
  }
  core_front.swap(next);
  const auto advance = [&](std::vector<int64_t>& front, bool freeze) {
    next.clear();
    for (int64_t i : front) {
      for (int64_t off : faces) {
        const int64_t j = i + off;
        if (!passable(j) || seen.test(j) || (freeze && near_data(j))) continue;
        seen.set(j);
        if (freeze) {
          grid.set(j, kInsideFrozen);
          ++stats.band_frozen;
        }
        next.push_back(j);
      }
    }
    front.swap(next);
  };
  while (!outside_front.empty() || !core_front.empty()) {
    if (cancel.cancelled()) return cancelled();
    advance(outside_front, false);
    advance(core_front, true);
  }
  stats.frozen_voxels += stats.band_frozen;
  if (band != nullptr) {
    band->factor = k;
    band->coarse_dims = coarse.dims();
    band->coarse_voxels.clear();
    for (int64_t i = 0; i < coarse.size(); ++i)
      if (classes[i] == kCoarseBand) band->coarse_voxels.push_back(i);
  }
  stats.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return stats;
}

int64_t ReleaseGuardedBand(VoxelGrid& grid, const GuardedBand& band) {
  int64_t released = 0;
  const std::array<int, 3>& cd = band.coarse_dims;
  for (int64_t c : band.coarse_voxels) {
    const int cx = static_cast<int>(c % cd[0]), cy = static_cast<int>(c / cd[0] % cd[1]),
              cz = static_cast<int>(c / (static_cast<int64_t>(cd[0]) * cd[1]));
    ForFineOf(grid, band.factor, cx, cy, cz, [&](const Coord& f) {
      const int64_t i = grid.Index(f);
      if (grid.at(i) != kInsideFrozen) return;
      grid.set(i, kInsideSoft);
      ++released;
    });
  }
  return released;
}

int64_t ReleaseInteriorGuard(VoxelGrid& grid, int threads) {
  constexpr int64_t kSlab = int64_t{1} << 22;
  VoxelState* s = grid.mutable_states().data();
  const int64_t size = grid.size();
  const int64_t tasks = (size + kSlab - 1) / kSlab;
  std::vector<int64_t> released(std::max(threads, 1), 0);
  RunTasks(threads, tasks, [&](int worker, int64_t task) {
    const int64_t end = std::min(size, (task + 1) * kSlab);
    int64_t count = 0;
    for (int64_t i = task * kSlab; i < end; ++i) {
      const bool guarded = s[i] == kInsideFrozen;
      count += guarded;
      s[i] = guarded ? kInsideSoft : s[i];
    }
    released[worker] += count;
  });
  int64_t total = 0;
  for (int64_t c : released) total += c;
  return total;
}

}  // namespace membrane
