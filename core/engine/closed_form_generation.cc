#include "core/engine/closed_form_generation.h"

#include <algorithm>

#include "absl/status/status.h"
#include "core/engine/flat_bitset.h"
#include "core/engine/incursion_test.h"
#include "core/engine/plate.h"
#include "core/engine/state_planes.h"
#include "core/engine/topology_guard.h"

namespace membrane {
// The planes of a closed-form generation, named. The apply step's planes reuse planes of the
// sweeps that are not read again by then (free_cells once the squares are made, back, reach,
// the first square).
struct ClosedFormPlanes {
  explicit ClosedFormPlanes(WorkPlanes& p)
      : interior(p.interior()), out0(p.plane(0)), free_cells(p.plane(1)), out(p.plane(2)),
        back(p.plane(3)), reach(p.plane(4)), tmp(p.plane(5)), fresh(p.plane(6)),
        scratch_a(p.plane(7)), scratch_b(p.plane(8)),
        squares{&p.plane(9), &p.plane(10), &p.plane(5)},
        was_boundary_soft(p.plane(3)), adjacent(p.plane(4)), converted(p.plane(1)),
        near_hard(p.plane(9)) {}
  const FlatBitset& interior;
  FlatBitset &out0, &free_cells, &out, &back, &reach, &tmp, &fresh, &scratch_a, &scratch_b;
  FlatBitset* squares[3];  // per plate axis; the third reuses `tmp` once it is free
  FlatBitset &was_boundary_soft, &adjacent, &converted, &near_hard;  // the apply step's
};

absl::StatusOr<ClosedFormOutcome> RunClosedFormGeneration(VoxelGrid& grid,
                                                          const ChainOptions& options,
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

  const FlatBitset& interior = ws.interior;
  FlatBitset& out0 = ws.out0;
  FillStatePlane(grid.states(), StatePredicate::kOutside, out0);
  if (cancel.cancelled()) return absl::CancelledError("cancelled in a closed-form generation");
  // FREE: cells a plate may cover: no hard or frozen voxel, off the array border. Inside
  // and boundary only prune no-op plates (fast-shrink.md section 4), so both count.
  FlatBitset& free_cells = ws.free_cells;
  FillStatePlane(grid.states(), StatePredicate::kFree, free_cells);
  free_cells.And(interior);

  FlatBitset& out = ws.out;
  out = out0;
  // Anchors of all-free n x n squares per plate axis (both signs share them): the erosion
  // along z serves the x and y axes, so four runs make the three planes. The *From runs fold
  // a plane copy into their first pass.
  FlatBitset* const* squares = ws.squares;
  FlatBitset& eroded_z = ws.tmp;
  FlatBitset& scratch = ws.scratch_a;  // for the runs; SpreadAlong's only when it runs
  eroded_z.ErodeRunFrom(free_cells, n, st[2], scratch);
  squares[0]->ErodeRunFrom(eroded_z, n, st[1], scratch);  // x: in-plane y, z
  squares[1]->ErodeRunFrom(eroded_z, n, st[0], scratch);  // y: in-plane z, x
  squares[2]->ErodeRunFrom(free_cells, n, st[0], scratch);  // overwrites eroded_z
  squares[2]->ErodeRun(n, st[1], scratch);                  // z: in-plane x, y
  bool square_fits[3];
  for (int a = 0; a < 3; ++a) square_fits[a] = squares[a]->any();
  if (cancel.cancelled()) return absl::CancelledError("cancelled in a closed-form generation");

  FlatBitset& back = ws.back;
  FlatBitset& reach = ws.reach;
  FlatBitset& reach_back = ws.fresh;  // free until the apply step
  // An axis whose last sweep added nothing, with `out` unchanged since, would add nothing
  // again: it is skipped. `out_version` counts the sweeps that changed `out`; `stable_at[a]`
  // is the version at which axis a last added nothing (-1: not yet).
  int64_t out_version = 0;
  int64_t stable_at[3] = {-1, -1, -1};
  for (bool changed = true; changed && outcome.rounds < 64;) {
    changed = false;
    ++outcome.rounds;
    for (int a = 0; a < 3; ++a) {
      if (!square_fits[a] || stable_at[a] == out_version) continue;
      if (cancel.cancelled()) return absl::CancelledError("cancelled in a closed-form generation");
      const int64_t sa = st[a], su = st[(a + 1) % 3], sv = st[(a + 2) % 3];
      // Plates whose back square (one layer behind, against the front) is all outside. Both
      // fronts of the axis use the same eroded plane: a step of the least fixed point only
      // needs its plates valid for the current `out`, so updating `out` after both (rather
      // than between them) reaches the same fixed point.
      back.ErodeRunFrom(out, n, su, scratch);
      back.ErodeRun(n, sv, scratch);
      if (cancel.cancelled()) return absl::CancelledError("cancelled in a closed-form generation");
      // Dig straight on: a plate whose back plate was contracted fits if its square is free.
      reach.AssignAndShifted(*squares[a], back, sa);
      reach.SpreadAlong(*squares[a], sa, grid.dim(a), ws.scratch_a, ws.scratch_b);
      reach_back.AssignAndShifted(*squares[a], back, -sa);
      reach_back.SpreadAlong(*squares[a], -sa, grid.dim(a), ws.scratch_a, ws.scratch_b);
      reach.Or(reach_back);
      if (cancel.cancelled()) return absl::CancelledError("cancelled in a closed-form generation");
      // Cells covered by the plates reached (dilation distributes over the union).
      reach.DilateRun(n, sv, scratch);
      reach.DilateRun(n, su, scratch);
      if (out.OrChanged(reach)) {
        changed = true;
        ++out_version;
      } else {
        stable_at[a] = out_version;
      }
    }
  }

  if (cancel.cancelled()) return absl::CancelledError("cancelled in a closed-form generation");
  // Apply: new outside voxels, and their inside 26-neighbours become boundary.
  FlatBitset& fresh = ws.fresh;
  fresh = out;
  fresh.AndNot(out0);
  outcome.new_outside = fresh.Count();
  if (outcome.new_outside == 0) {
    outcome.applied = true;
    return outcome;
  }
  FlatBitset& was_boundary_soft = ws.was_boundary_soft;
  FillStatePlane(grid.states(), StatePredicate::kBoundarySoft, was_boundary_soft);
  FlatBitset& adjacent = ws.adjacent;
  adjacent = fresh;
  adjacent.Dilate26(strides, ws.scratch_a);
  adjacent.AndNot(out);
  VoxelState* s = grid.mutable_states().data();
  const VoxelState label = OutsideState(options.generation_label);
  fresh.ForEach([&](int64_t i) { s[i] = label; });
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
    fresh.ForEach([&](int64_t i) { s[i] = was_boundary_soft.test(i) ? kBoundarySoft : kInsideSoft; });
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
    FlatBitset& near_hard = ws.near_hard;
    FillStatePlane(grid.states(), StatePredicate::kHard, near_hard);
    near_hard.Dilate26(strides, ws.scratch_a);
    near_hard.And(fresh);
    const GuardOptions& guard = options.guard;
    near_hard.ForEach([&](int64_t i) {
      if (cancelled || outcome.guard_refusals > 0) return;
      if ((++outcome.checks & 4095) == 0 && cancel.cancelled()) cancelled = true;
      if (!GuardAllowsRemoval(grid, i, guard)) ++outcome.guard_refusals;
    });
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
