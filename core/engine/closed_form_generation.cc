#include "core/engine/closed_form_generation.h"

#include <algorithm>
#include <array>
#include <cstring>
#include <optional>
#include <vector>

#include "absl/status/status.h"
#include "core/engine/closed_form_sweeps.h"
#include "core/engine/flat_bitset.h"
#include "core/engine/incursion_test.h"
#include "core/engine/interior_plane.h"
#include "core/engine/plate.h"
#include "core/engine/state_planes.h"
#include "core/engine/topology_guard.h"

namespace membrane {
namespace {

// s[i] = state for every set bit i of `cells`: a whole word of set bits (the bulk of a first
// generation's hundreds of millions) is one 64-byte fill.
void SetStatesOf(const FlatBitset& cells, VoxelState state, VoxelState* s) {
  const uint64_t* w = cells.words();
  for (size_t k = 0; k < cells.word_count(); ++k) {
    uint64_t bits = w[k];
    if (bits == ~uint64_t{0}) {
      std::memset(s + 64 * static_cast<int64_t>(k), state, 64);
      continue;
    }
    while (bits != 0) {
      s[64 * static_cast<int64_t>(k) + __builtin_ctzll(bits)] = state;
      bits &= bits - 1;
    }
  }
}

}  // namespace

// The planes of a closed-form generation, named: kClosedFormPlanes of them. The squares are
// made from the free cells, whose plane then holds the second front's reach; the apply step
// reuses the planes of the sweeps that are not read again by then (out stays).
struct ClosedFormPlanes {
  explicit ClosedFormPlanes(WorkPlanes& p)
      : free_cells(p.plane(0)), out(p.plane(1)), back(p.plane(2)), reach(p.plane(3)),
        reach_back(p.plane(0)), scratch(p.plane(4)),
        squares{&p.plane(5), &p.plane(6), &p.plane(7)},
        fresh(p.plane(0)), old_outside(p.plane(2)), was_boundary_soft(p.plane(2)),
        adjacent(p.plane(3)), converted(p.plane(5)), near_hard(p.plane(6)) {}
  FlatBitset &free_cells, &out, &back, &reach, &reach_back, &scratch;
  // Per plate axis; the third also holds the erosion along z the first two are made from.
  FlatBitset* squares[3];
  // The apply step's (old_outside is read before was_boundary_soft is written).
  FlatBitset &fresh, &old_outside, &was_boundary_soft, &adjacent, &converted, &near_hard;
};

absl::StatusOr<ClosedFormOutcome> RunClosedFormGeneration(VoxelGrid& grid,
                                                          const ChainOptions& options,
                                                          int64_t voxelwise_max,
                                                          const CancelToken& cancel,
                                                          WorkPlanes& planes) {
  const int n = options.plate_size();
  const auto st = grid.strides();
  const int64_t strides[3] = {st[0], st[1], st[2]};
  ClosedFormOutcome outcome;
  if (!planes.Ensure(kClosedFormPlanes, cancel)) {
    return absl::CancelledError("cancelled in a closed-form generation");
  }
  ClosedFormPlanes ws(planes);

  // FREE: cells a plate may cover: no hard or frozen voxel, off the array border. Inside
  // and boundary only prune no-op plates (fast-shrink.md section 4), so both count.
  FlatBitset& free_cells = ws.free_cells;
  FillStatePlane(grid.states(), StatePredicate::kFree, free_cells);
  ClearArrayBorder(grid.dims(), free_cells);
  if (cancel.cancelled()) return absl::CancelledError("cancelled in a closed-form generation");
  // Anchors of all-free n x n squares per plate axis (both signs share them), then the
  // sweeps' rounds until `out` is the fixed point.
  const PlaneBox box = MakePlaneBox(grid.dims());
  FreeSquares(free_cells, n, box, ws.squares, ws.scratch);
  if (cancel.cancelled()) return absl::CancelledError("cancelled in a closed-form generation");
  FlatBitset& out = ws.out;
  FillStatePlane(grid.states(), StatePredicate::kOutside, out);
  const SweepPlanes sweep{{ws.squares[0], ws.squares[1], ws.squares[2]}, &ws.back, &ws.reach,
                          &ws.reach_back, &ws.scratch};
  const std::optional<int> rounds = SweepToFixedPoint(out, n, box, sweep, cancel);
  if (!rounds) return absl::CancelledError("cancelled in a closed-form generation");
  outcome.rounds = *rounds;

  if (cancel.cancelled()) return absl::CancelledError("cancelled in a closed-form generation");
  // Apply: new outside voxels, and their inside 26-neighbours become boundary.
  // The grid is as it was before the sweeps: its outside voxels are the ones they started from.
  FlatBitset& old_outside = ws.old_outside;
  FillStatePlane(grid.states(), StatePredicate::kOutside, old_outside);
  FlatBitset& fresh = ws.fresh;
  fresh = out;
  fresh.AndNot(old_outside);
  outcome.new_outside = fresh.Count();
  if (outcome.new_outside == 0) {
    outcome.applied = true;
    return outcome;
  }
  VoxelState* s = grid.mutable_states().data();
  const VoxelState label = OutsideState(options.generation_label);
  // A generation that adds few voxels (every one after the membrane reached the data) reads
  // their 26 neighbours voxel by voxel: the planes' dilations and fills cost about twenty
  // passes over the whole grid however few voxels changed. Both ways give the same sets, and
  // visit them in the same (increasing) order.
  const bool sparse = outcome.new_outside <= voxelwise_max;
  outcome.voxelwise = sparse;
  const std::array<int64_t, 26>& neighbours = grid.neighbour_offsets();
  std::vector<int64_t> fresh_list;
  std::vector<VoxelState> fresh_before;  // sparse: each fresh voxel's state before the apply
  FlatBitset& was_boundary_soft = ws.was_boundary_soft;
  FlatBitset& adjacent = ws.adjacent;
  if (sparse) {
    fresh_list.reserve(static_cast<size_t>(outcome.new_outside));
    fresh.ForEach([&](int64_t i) { fresh_list.push_back(i); });
    fresh_before.reserve(fresh_list.size());
    adjacent.clear_all();
    for (int64_t i : fresh_list) {
      fresh_before.push_back(s[i]);
      for (int64_t o : neighbours) {
        if (!out.test(i + o)) adjacent.set(i + o);
      }
    }
    for (int64_t i : fresh_list) s[i] = label;
  } else {
    FillStatePlane(grid.states(), StatePredicate::kBoundarySoft, was_boundary_soft);
    adjacent = fresh;
    adjacent.Dilate26(strides, ws.scratch);
    adjacent.AndNot(out);
    SetStatesOf(fresh, label, s);
  }
  FlatBitset& converted = ws.converted;
  converted.clear_all();
  adjacent.ForEach([&](int64_t i) {
    if (IsInside(s[i])) {
      s[i] |= kBoundaryBit;
      converted.set(i);
    }
  });

  // Rejected or cancelled: restore, and (when rejected) let the chains run this generation.
  auto restore = [&] {
    if (sparse) {
      for (size_t k = 0; k < fresh_list.size(); ++k) s[fresh_list[k]] = fresh_before[k];
    } else {
      fresh.ForEach(
          [&](int64_t i) { s[i] = was_boundary_soft.test(i) ? kBoundarySoft : kInsideSoft; });
    }
    converted.ForEach([&](int64_t i) { s[i] &= static_cast<VoxelState>(~kBoundaryBit); });
  };
  // Checks: the incursion test where the neighbourhood changed, and the guard on the new
  // outside voxels next to hard ones, each as if it were the last removal. The cancel token is
  // polled every few thousand checks: a first generation may check a million voxels.
  bool cancelled = false;
  adjacent.ForEach([&](int64_t i) {
    if (cancelled || outcome.incursions > 0 || !IsHardOrFrozen(s[i])) return;
    if ((++outcome.checks & 4095) == 0 && cancel.cancelled()) cancelled = true;
    if (IncursionAt(grid, i, options.rules.thick_wall_run, options.thin_part()))
      ++outcome.incursions;
  });
  if (!cancelled && outcome.incursions == 0 && options.rules.topology_guard) {
    const GuardOptions& guard = options.guard;
    auto check = [&](int64_t i) {
      if (cancelled || outcome.guard_refusals > 0) return;
      if ((++outcome.checks & 4095) == 0 && cancel.cancelled()) cancelled = true;
      if (!GuardAllowsRemoval(grid, i, guard)) ++outcome.guard_refusals;
    };
    if (sparse) {
      for (int64_t i : fresh_list) {
        for (int64_t o : neighbours) {
          if (IsHard(s[i + o])) {
            check(i);
            break;
          }
        }
      }
    } else {
      FlatBitset& near_hard = ws.near_hard;
      FillStatePlane(grid.states(), StatePredicate::kHard, near_hard);
      near_hard.Dilate26(strides, ws.scratch);
      near_hard.And(fresh);
      near_hard.ForEach(check);
    }
  }
  if (cancelled) {
    restore();
    return absl::CancelledError("cancelled in a closed-form generation");
  }
  if (outcome.incursions == 0 && outcome.guard_refusals == 0) {
    outcome.applied = true;
    return outcome;
  }
  restore();
  return outcome;
}

}  // namespace membrane
