#include "core/engine/interior_guard.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <utility>
#include <vector>

#include "absl/status/status.h"
#include "core/base/parallel_tasks.h"
#include "core/engine/coarse_grid.h"
#include "core/engine/flat_bitset.h"
#include "core/engine/gap_refill.h"
#include "core/engine/guard_band_waves.h"
#include "core/engine/membrane_shrinker.h"
#include "core/engine/point_gap_split.h"
#include "core/engine/shrink_options.h"
#include "core/engine/state_planes.h"
#include "core/engine/voxelization.h"

namespace membrane {
namespace {

constexpr int kPad = VoxelGrid::kPadding;

// A band of fewer coarse voxels than this is released on the calling thread: starting a thread
// costs more than their fine voxels (64 each at the factor 4).
constexpr int64_t kMinCoarseVoxelsToSplit = 1024;

// Marks of a grid's voxels, one byte each.
using Marks = std::vector<uint8_t>;

// For every voxel, how many of its 6 axis rays reach an outside voxel before a hard one (the
// array border counts as outside): 0 to 6. An axis's lines run on `threads`, a plane of
// lines a task.
Marks OpenRays(const VoxelGrid& grid, int threads) {
  const std::array<int, 3>& dims = grid.dims();
  const std::array<int64_t, 3> strides = grid.strides();
  Marks open(grid.size(), 0);
  for (int axis = 0; axis < 3; ++axis) {
    const int a1 = axis == 0 ? 1 : 0, a2 = axis == 2 ? 1 : 2;
    const int n = dims[axis];
    RunTasks(threads, dims[a2], [&](int, int64_t j) {
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
    });
  }
  return open;
}

// Calls visit(fine coord) for every fine voxel of the data region in coarse voxel (cx, cy, cz).
template <typename Visit>
void ForFineOf(const VoxelGrid& fine, int k, int cx, int cy, int cz, Visit visit) {
  const int x0 = kPad + (cx - kPad) * k, y0 = kPad + (cy - kPad) * k, z0 = kPad + (cz - kPad) * k;
  for (int z = z0; z < std::min(z0 + k, fine.dim(2) - kPad); ++z)
    for (int y = y0; y < std::min(y0 + k, fine.dim(1) - kPad); ++y)
      for (int x = x0; x < std::min(x0 + k, fine.dim(0) - kPad); ++x) visit(Coord{x, y, z});
}

// Freezes the fine INSIDE soft voxels of the coarse voxels classed kCoarseCore, a coarse z
// plane a task on `threads` (each task writes its own fine planes); returns how many.
int64_t FreezeCore(VoxelGrid& grid, const VoxelGrid& coarse, int k, const Marks& classes,
                   int threads) {
  const std::array<int, 3>& cd = coarse.dims();
  VoxelState* states = grid.mutable_states().data();
  std::vector<int64_t> counts(static_cast<size_t>(threads), 0);
  RunTasks(threads, cd[2] - 2 * kPad, [&](int worker, int64_t task) {
    const int cz = kPad + static_cast<int>(task);
    const int z1 = std::min(kPad + (cz - kPad + 1) * k, grid.dim(2) - kPad);
    int64_t count = 0;
    for (int z = kPad + (cz - kPad) * k; z < z1; ++z) {
      for (int y = kPad; y < grid.dim(1) - kPad; ++y) {
        const uint8_t* row_classes = classes.data() + coarse.Index(0, (y - kPad) / k + kPad, cz);
        VoxelState* row = states + grid.Index(0, y, z);
        for (int cx = kPad; cx < cd[0] - kPad; ++cx) {
          if (row_classes[cx] != kCoarseCore) continue;
          const int x0 = kPad + (cx - kPad) * k, x1 = std::min(x0 + k, grid.dim(0) - kPad);
          for (int x = x0; x < x1; ++x) {
            const bool soft = row[x] == kInsideSoft;
            count += soft;
            row[x] = soft ? kInsideFrozen : row[x];
          }
        }
      }
    }
    counts[static_cast<size_t>(worker)] += count;
  });
  int64_t total = 0;
  for (int64_t c : counts) total += c;
  return total;
}

}  // namespace

InteriorGuardOptions DenseScanGuard(InteriorGuardOptions options) {
  options.min_coarse_axis = std::min(options.min_coarse_axis, kDenseScanMinCoarseAxis);
  options.max_open_rays = std::min(options.max_open_rays, kDenseScanMaxOpenRays);
  options.one_piece_only = true;
  return options;
}

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
  if (o.one_piece_only) {
    absl::StatusOr<DataPieces> pieces =
        FindDataPieces(grid, nullptr, 0, options.separation.min_piece_fraction, cancel);
    if (!pieces.ok()) return pieces.status();
    if (pieces->count >= 2) return stats;
  }

  // The coarse membrane, refilled where it carved through data gaps; no dents (they would cut
  // paths into the solid that the fine membrane has no reason to follow).
  // The fine grid's passes run on the shrink's threads where its own passes do.
  const int threads =
      grid.size() >= options.threads_min_voxels ? std::max(options.threads, 1) : 1;
  VoxelGrid coarse = CoarseGrid(grid, k, threads);
  ShrinkOptions coarse_options = options;
  coarse_options.connect_inside_hard = false;
  // No guard of its own: on a grid 16 times coarser a coarse voxel is hard when one of 4096
  // fine ones is, the barely seen inner sides of close parts (a cow's four legs) join into
  // walls, and the space they enclose is held as an interior down to the fine grid, where the
  // membrane spans it as a web (docs/engine-decisions.md, "Interiors held by a coarser
  // membrane").
  coarse_options.interior_guard.enabled = false;
  absl::StatusOr<ShrinkResult> shrunk = ShrinkMembrane(coarse, {}, coarse_options, {}, cancel);
  if (!shrunk.ok()) return shrunk.status();
  stats.levels = 1;

  // Hard voxels and their 26 neighbours (the padding keeps every hard voxel off the array
  // border, so the dilation does not wrap).
  FlatBitset near_hard(coarse.size()), scratch(coarse.size());
  FillStatePlane(coarse.states(), StatePredicate::kHard, near_hard);
  {
    const std::array<int64_t, 3> st = coarse.strides();
    const int64_t strides[3] = {st[0], st[1], st[2]};
    near_hard.Dilate26(strides, scratch);
  }
  const Marks open_rays = OpenRays(coarse, threads);
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

  // The core: every fine voxel of it is frozen.
  stats.frozen_voxels = FreezeCore(grid, coarse, k, classes, threads);
  if (cancel.cancelled()) return cancelled();

  // The band between the core and the coarse outside holds the skin's data. Its fine soft
  // voxels are split by which side reaches them first through soft voxels: two breadth-first
  // waves, from the coarse outside and from the core, the outside's first at each distance
  // (a tie stays soft). The core's wave stops at the skin's data from inside and meets the
  // outside's in the skin's pores; its voxels are frozen.
  std::vector<int64_t> band_voxels;
  for (int64_t i = 0; i < coarse.size(); ++i)
    if (classes[i] == kCoarseBand) band_voxels.push_back(i);
  absl::StatusOr<int64_t> band_frozen =
      FreezeBandByWaves(grid, coarse.dims(), k, classes, band_voxels, cancel, threads);
  if (!band_frozen.ok()) return band_frozen.status();
  stats.band_frozen = *band_frozen;
  stats.frozen_voxels += stats.band_frozen;
  if (band != nullptr) {
    band->factor = k;
    band->coarse_dims = coarse.dims();
    band->coarse_voxels = std::move(band_voxels);
    band->held = true;
  }
  stats.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return stats;
}

int64_t ReleaseGuardedBand(VoxelGrid& grid, GuardedBand& band, int threads) {
  if (!band.held) return 0;
  band.held = false;
  const std::array<int, 3>& cd = band.coarse_dims;
  // A range of coarse voxels a task: the coarse voxels are distinct, so each task writes fine
  // voxels no other task reads or writes.
  const TaskRanges ranges = TaskRanges::Split(static_cast<int64_t>(band.coarse_voxels.size()),
                                              threads, 4, kMinCoarseVoxelsToSplit);
  std::vector<int64_t> released(static_cast<size_t>(ranges.tasks), 0);
  RunTasks(threads, ranges.tasks, [&](int, int64_t task) {
    int64_t n = 0;
    for (int64_t j = ranges.begin(task); j < ranges.end(task); ++j) {
      const int64_t c = band.coarse_voxels[static_cast<size_t>(j)];
      const int cx = static_cast<int>(c % cd[0]), cy = static_cast<int>(c / cd[0] % cd[1]),
                cz = static_cast<int>(c / (static_cast<int64_t>(cd[0]) * cd[1]));
      ForFineOf(grid, band.factor, cx, cy, cz, [&](const Coord& f) {
        const int64_t i = grid.Index(f);
        if (grid.at(i) != kInsideFrozen) return;
        grid.set(i, kInsideSoft);
        ++n;
      });
    }
    released[static_cast<size_t>(task)] = n;
  });
  int64_t total = 0;
  for (int64_t n : released) total += n;
  return total;
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
