#include "core/engine/closed_form_generation.h"

#include <algorithm>
#include <array>
#include <cstring>
#include <optional>
#include <vector>

#include "absl/status/status.h"
#include "core/engine/closed_form_sweeps.h"
#include "core/engine/first_failure.h"
#include "core/engine/flat_bitset.h"
#include "core/engine/incursion_test.h"
#include "core/engine/interior_plane.h"
#include "core/engine/plate.h"
#include "core/engine/state_planes.h"
#include "core/engine/topology_guard.h"
#include "core/engine/word_blocks.h"

namespace membrane {
namespace {

// s[i] = state for every set bit i of `cells`: a whole word of set bits (the bulk of a first
// generation's hundreds of millions) is one 64-byte fill. Blocks of words on `threads`: each
// writes the states of its own words' voxels.
void SetStatesOf(const FlatBitset& cells, VoxelState state, VoxelState* s, int threads) {
  const uint64_t* w = cells.words();
  ForWordBlocks(threads, static_cast<int64_t>(cells.word_count()),
                [&](int64_t, int64_t begin, int64_t end) {
                  for (int64_t k = begin; k < end; ++k) {
                    uint64_t bits = w[k];
                    if (bits == ~uint64_t{0}) {
                      std::memset(s + 64 * k, state, 64);
                      continue;
                    }
                    while (bits != 0) {
                      s[64 * k + __builtin_ctzll(bits)] = state;
                      bits &= bits - 1;
                    }
                  }
                });
}

// Every inside voxel of `adjacent` becomes boundary and is set in `converted` (clear before).
// Blocks of words on `threads`: a voxel's state and bit are its word's block's alone.
void ConvertToBoundary(const FlatBitset& adjacent, VoxelState* s, FlatBitset& converted,
                       int threads) {
  ForWordBlocks(threads, static_cast<int64_t>(adjacent.word_count()),
                [&](int64_t, int64_t begin, int64_t end) {
                  adjacent.ForEachInWords(begin, end, [&](int64_t i) {
                    if (IsInside(s[i])) {
                      s[i] |= kBoundaryBit;
                      converted.set(i);
                    }
                    return true;
                  });
                });
}

// Undoes the planes' apply of a rejected (or cancelled) result: every voxel of `fresh` gets
// back its soft state (boundary where `was_boundary_soft`, inside elsewhere) and every voxel
// of `converted` loses the boundary bit. Blocks of words on `threads`: a voxel's bits are its
// word's block's alone, and `fresh` (outside after the sweeps) and `converted` (not outside)
// share no voxel, so the grid is the same for any count.
void RestoreStates(const FlatBitset& fresh, const FlatBitset& was_boundary_soft,
                   const FlatBitset& converted, VoxelState* s, int threads) {
  ForWordBlocks(threads, static_cast<int64_t>(fresh.word_count()),
                [&](int64_t, int64_t begin, int64_t end) {
                  fresh.ForEachInWords(begin, end, [&](int64_t i) {
                    s[i] = was_boundary_soft.test(i) ? kBoundarySoft : kInsideSoft;
                    return true;
                  });
                  converted.ForEachInWords(begin, end, [&](int64_t i) {
                    s[i] &= static_cast<VoxelState>(~kBoundaryBit);
                    return true;
                  });
                });
}

// Spans the closed form's checks are split into: one on one thread or for fewer than 2^12
// items (a grid of a few hundred thousand voxels, a short list), where starting threads costs
// more than the checks; otherwise 64 a thread, so that a span after an early refusal stops
// soon.
int64_t CheckSpans(int64_t items, int threads) {
  if (threads <= 1 || items < (int64_t{1} << 12)) return 1;
  return std::min<int64_t>(items, int64_t{64} * threads);
}

// Calls visit(i) for the set bits i of `set` in words [words * span / spans, words * (span +
// 1) / spans), in increasing order, until visit returns false.
template <typename Visit>
void ForBitsOfSpan(const FlatBitset& set, int64_t span, int64_t spans, Visit visit) {
  const int64_t words = static_cast<int64_t>(set.word_count());
  set.ForEachInWords(words * span / spans, words * (span + 1) / spans, visit);
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
    SetStatesOf(fresh, label, s, planes.threads());
  }
  FlatBitset& converted = ws.converted;
  converted.clear_all();
  ConvertToBoundary(adjacent, s, converted, planes.threads());

  // Rejected or cancelled: restore, and (when rejected) let the chains run this generation.
  auto restore = [&] {
    if (!sparse) {
      RestoreStates(fresh, was_boundary_soft, converted, s, planes.threads());
      return;
    }
    for (size_t k = 0; k < fresh_list.size(); ++k) s[fresh_list[k]] = fresh_before[k];
    converted.ForEach([&](int64_t i) { s[i] &= static_cast<VoxelState>(~kBoundaryBit); });
  };
  // Checks: the incursion test where the neighbourhood changed, and the guard on the new
  // outside voxels next to hard ones (on every new outside voxel below the object's tunnel
  // plate, where tunnels away from the data need data around them), each as if it were the
  // last removal, in increasing voxel order up to the first refusal. They only read the grid:
  // spans of the candidates run on the planes' threads, with the counts of the scan in order
  // (first_failure.h).
  const int threads = planes.threads();
  const int64_t word_spans = CheckSpans(static_cast<int64_t>(adjacent.word_count()), threads);
  const FirstFailure incursion = FindFirstFailure(
      word_spans, threads, cancel,
      [&](int64_t span, auto visit) {
        ForBitsOfSpan(adjacent, span, word_spans,
                      [&](int64_t i) { return !IsHardOrFrozen(s[i]) || visit(i); });
      },
      [&](int64_t i) {
        return IncursionAt(grid, i, options.rules.thick_wall_run, options.thin_part());
      });
  outcome.checks = incursion.tested;
  outcome.incursions = incursion.failed ? 1 : 0;
  bool cancelled = incursion.cancelled;
  if (!cancelled && outcome.incursions == 0 && options.rules.topology_guard) {
    const GuardOptions& guard = options.guard;
    auto refused = [&](int64_t i) { return !GuardAllowsRemoval(grid, i, guard); };
    const bool every_voxel = guard.plate_size < guard.sizes.object_tunnel_plate;
    FirstFailure refusal;
    if (sparse) {
      // The new outside voxels with a hard 26-neighbour (every one below the object's tunnel
      // plate), in the list's (increasing) order.
      const int64_t items = static_cast<int64_t>(fresh_list.size());
      const int64_t spans = CheckSpans(items, threads);
      refusal = FindFirstFailure(
          spans, threads, cancel,
          [&](int64_t span, auto visit) {
            for (int64_t k = items * span / spans; k < items * (span + 1) / spans; ++k) {
              const int64_t i = fresh_list[static_cast<size_t>(k)];
              const bool near_hard = std::any_of(neighbours.begin(), neighbours.end(),
                                                 [&](int64_t o) { return IsHard(s[i + o]); });
              if ((every_voxel || near_hard) && !visit(i)) return;
            }
          },
          refused);
    } else {
      FlatBitset& checked = ws.near_hard;
      if (every_voxel) {
        checked = fresh;
      } else {
        FillStatePlane(grid.states(), StatePredicate::kHard, checked);
        checked.Dilate26(strides, ws.scratch);
        checked.And(fresh);
      }
      refusal = FindFirstFailure(
          word_spans, threads, cancel,
          [&](int64_t span, auto visit) { ForBitsOfSpan(checked, span, word_spans, visit); },
          refused);
    }
    outcome.checks += refusal.tested;
    outcome.guard_refusals = refusal.failed ? 1 : 0;
    cancelled = refusal.cancelled;
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
