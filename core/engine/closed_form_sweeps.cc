#include "core/engine/closed_form_sweeps.h"

namespace membrane {

PlaneBox MakePlaneBox(const std::array<int, 3>& dims) {
  PlaneBox box;
  box.dims = dims;
  box.strides = {1, dims[0], static_cast<int64_t>(dims[0]) * dims[1]};
  return box;
}

void FreeSquares(const FlatBitset& free_cells, int n, const PlaneBox& box,
                 FlatBitset* const squares[3], FlatBitset& scratch) {
  const auto& st = box.strides;
  // The erosion along z serves the x and y axes, so four runs make the three planes. The
  // *From runs fold a plane copy into their first pass.
  FlatBitset& eroded_z = *squares[2];
  eroded_z.ErodeRunFrom(free_cells, n, st[2], scratch);
  squares[0]->ErodeRunFrom(eroded_z, n, st[1], scratch);  // x: in-plane y, z
  squares[1]->ErodeRunFrom(eroded_z, n, st[0], scratch);  // y: in-plane z, x
  // z: in-plane x, y. Erosions along two axes commute; along y first, from another plane, a
  // long run's cell passes run side by side (the one along x is no such run below n = 64).
  squares[2]->ErodeRunFrom(free_cells, n, st[1], scratch);  // overwrites eroded_z
  squares[2]->ErodeRun(n, st[0], scratch);
}

std::optional<int> SweepToFixedPoint(FlatBitset& out, int n, const PlaneBox& box,
                                     const SweepPlanes& planes, const CancelToken& cancel) {
  const auto& st = box.strides;
  bool square_fits[3];
  for (int a = 0; a < 3; ++a) square_fits[a] = planes.squares[a]->any();
  FlatBitset& back = *planes.back;
  FlatBitset& reach = *planes.reach;
  FlatBitset& reach_back = *planes.reach_back;
  FlatBitset& scratch = *planes.scratch;
  // An axis whose last sweep added nothing, with `out` unchanged since, would add nothing
  // again: it is skipped. `out_version` counts the sweeps that changed `out`; `stable_at[a]`
  // is the version at which axis a last added nothing (-1: not yet).
  int64_t out_version = 0;
  int64_t stable_at[3] = {-1, -1, -1};
  int rounds = 0;
  for (bool changed = true; changed && rounds < 64;) {
    changed = false;
    ++rounds;
    for (int a = 0; a < 3; ++a) {
      if (!square_fits[a] || stable_at[a] == out_version) continue;
      if (cancel.cancelled()) return std::nullopt;
      const FlatBitset& squares = *planes.squares[a];
      const int64_t sa = st[a], su = st[(a + 1) % 3], sv = st[(a + 2) % 3];
      // Plates whose back square (one layer behind, against the front) is all outside. Both
      // fronts of the axis use the same eroded plane: a step of the least fixed point only
      // needs its plates valid for the current `out`, so updating `out` after both (rather
      // than between them) reaches the same fixed point.
      // Each run reads another plane than it writes (reach_back is free until the seeds):
      // in place, a long run's two cell passes (flat_bitset_long_runs.cc) follow each other on
      // one thread; from another plane they run side by side.
      reach_back.ErodeRunFrom(out, n, su, scratch);
      back.ErodeRunFrom(reach_back, n, sv, scratch);
      if (cancel.cancelled()) return std::nullopt;
      // Dig straight on: a plate whose back plate was contracted fits if its square is free.
      // Both fronts' seeds first: `back` is then free to serve the spreads as scratch.
      reach.AssignAndShifted(squares, back, sa);
      reach_back.AssignAndShifted(squares, back, -sa);
      reach.SpreadAlong(squares, sa, box.dims[a], scratch, back);
      reach_back.SpreadAlong(squares, -sa, box.dims[a], scratch, back);
      reach.Or(reach_back);
      if (cancel.cancelled()) return std::nullopt;
      // Cells covered by the plates reached (dilation distributes over the union), through
      // `back`, free again, for the same reason.
      back.DilateRunFrom(reach, n, sv, scratch);
      reach.DilateRunFrom(back, n, su, scratch);
      if (out.OrChanged(reach)) {
        changed = true;
        ++out_version;
      } else {
        stable_at[a] = out_version;
      }
    }
  }
  return rounds;
}

}  // namespace membrane
