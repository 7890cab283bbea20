#include "core/engine/place_finder.h"

#include <algorithm>
#include <bit>

#include "core/engine/first_anchored_plate.h"
#include "core/engine/interior_plane.h"
#include "core/engine/state_planes.h"

namespace membrane {

// Every plane of a snapshot comes from the arena (the closed form needs as many).
static_assert(kPlaceFinderPlanes <= WorkPlanes::kArenaPlanes);

PlaceFinder::PlaceFinder(const VoxelGrid& grid, WorkPlanes& planes)
    : grid_(grid), planes_(planes), local_(grid, planes.threads()) {}

std::optional<std::vector<int64_t>> PlaceFinder::SnapshotAfter(int n,
                                                               const std::vector<VoxelBox>& written,
                                                               const LocalSnapshotOptions& options,
                                                               const CancelToken& cancel) {
  if (n == n_) {
    local_taken_ = false;
    std::optional<std::vector<int64_t>> local = local_.Take(n, written, options, cancel);
    if (local) {
      local_taken_ = true;
      // The dense anchors are stale. Below kAnchorRowsMinPlate they are freed: the later
      // passes and the handle retry take their room. From it on their buffers are kept for
      // the next dense pass to reuse: freed, they were made again in fresh memory.
      if (n < kAnchorRowsMinPlate) anchors_ = {};
      return local;
    }
    if (cancel.cancelled()) return std::nullopt;
  }
  return Snapshot(n, cancel);
}

std::optional<std::vector<int64_t>> PlaceFinder::Snapshot(int n, const CancelToken& cancel) {
  local_taken_ = false;
  rows_ = n >= kAnchorRowsMinPlate;
  if (!planes_.Ensure(kPlaceFinderPlanes, cancel)) return std::nullopt;
  n_ = n;
  const auto st = grid_.strides();
  FlatBitset& free_cells = planes_.plane(0);  // outside or boundary soft, off the border
  FlatBitset& out = planes_.plane(1);
  FillFreeAndOutsidePlanes(grid_.states(), free_cells, out);
  if (cancel.cancelled()) return std::nullopt;
  ClearArrayBorder(grid_.dims(), free_cells);

  // The anchors of orientation (a, sign) are the plates whose cells are free and whose back
  // side is outside: E = erode_uv(free & out shifted by sign along a), and erosion commutes
  // with the shift and distributes over &, so E = erode_uv(free) & (erode_uv(out) shifted).
  // Both signs share the two eroded planes, and the three axes share the erosions along z
  // and along x: 8 erosion runs instead of 12. Copies are folded into the first pass of each
  // run (the *From operations): the planes fit in cache, so a copy costs as much as a pass.
  // Runs along y and z of 17 and more take three passes instead of the doubling's six or
  // more (flat_bitset_long_runs.cc: the same bits), each with a plane the snapshot has not
  // filled yet or no longer reads as its scratch.
  FlatBitset& free_z = planes_.plane(2);
  FlatBitset& out_z = planes_.plane(3);
  free_z.ErodeRunFrom(free_cells, n, st[2], planes_.plane(4));
  out_z.ErodeRunFrom(out, n, st[2], planes_.plane(4));
  if (cancel.cancelled()) return std::nullopt;
  FlatBitset& free_x = free_cells;  // eroded in place: the plain planes are not needed again
  FlatBitset& out_x = out;
  free_x.ErodeRun(n, st[0], planes_.plane(4));
  out_x.ErodeRun(n, st[0], planes_.plane(4));

  // Candidates: bs & the union over axes of the cells covered by a plate of either sign
  // (And distributes over the union, so it is applied once at the end). Each orientation's
  // anchors are packed as soon as they are made, so that one plane at a time holds them.
  FlatBitset& candidates = planes_.plane(4);
  FlatBitset& free_square = planes_.plane(5);
  FlatBitset& out_square = planes_.plane(6);
  FlatBitset& second = planes_.plane(7);  // the second sign's anchors
  for (int a = 0; a < 3; ++a) {
    if (cancel.cancelled()) return std::nullopt;
    // In-plane axes (u, v) = (y, z), (z, x), (x, y): one more erosion of a shared plane.
    const bool from_z = a != 2;
    const int last_axis = a == 1 ? 0 : 1;
    free_square.ErodeRunFrom(from_z ? free_z : free_x, n, st[last_axis], second);
    out_square.ErodeRunFrom(from_z ? out_z : out_x, n, st[last_axis], second);
    const int64_t su = st[(a + 1) % 3], sv = st[(a + 2) % 3];
    // The cells covered by the axis' plates gather in the first sign's plane: the candidates
    // for the first axis, then the z-eroded free plane, which the squares of the second axis
    // were the last to read.
    FlatBitset& covered = a == 0 ? candidates : free_z;
    for (int o = 2 * a; o < 2 * a + 2; ++o) {
      const bool first_sign = o == 2 * a;
      FlatBitset& e = first_sign ? covered : second;
      e.AssignAndShifted(free_square, out_square, kOrientations[o].sign * st[a]);
      anchors_[o].Assign(e);
      // Dilation distributes over the union of both signs' plates: with rows, each sign is
      // dilated along v for its rows and the union is taken after. The second sign's plane
      // is free until its anchors are made, the squares once they are.
      if (rows_) {
        e.DilateRun(n, sv, first_sign ? second : free_square);
        anchor_rows_[o].Assign(e);
      }
    }
    covered.Or(second);
    if (!rows_) covered.DilateRun(n, sv, second);
    covered.DilateRun(n, su, second);
    if (a != 0) candidates.Or(covered);
  }
  if (!rows_) anchor_rows_ = {};  // a bigger plate's rows are not read again
  FlatBitset& bs = free_square;  // not read again
  FillStatePlane(grid_.states(), StatePredicate::kBoundarySoft, bs);
  candidates.And(bs);
  std::vector<int64_t> result;
  const uint64_t* cw = candidates.words();
  for (int64_t w = 0; w < static_cast<int64_t>(candidates.word_count()); ++w) {
    uint64_t bits = cw[w];
    while (bits != 0) {
      const int b = std::countr_zero(bits);
      bits &= bits - 1;
      result.push_back(w * 64 + b);
    }
  }
  return result;
}

void PlaceFinder::Release() {
  local_.Release();
  local_taken_ = false;
  anchors_ = {};
  anchor_rows_ = {};
  rows_ = false;
}

std::optional<Plate> PlaceFinder::PlaceFor(int64_t index) const {
  if (local_taken_) return local_.PlaceFor(index);
  return FirstAnchoredPlate(
      grid_.CoordOf(index), n_,
      [&](int o, const Coord& cell) { return anchors_[o].test(grid_.Index(cell)); },
      [&](int o, const Coord& cell) { return !rows_ || anchor_rows_[o].test(grid_.Index(cell)); });
}

}  // namespace membrane
