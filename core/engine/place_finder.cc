#include "core/engine/place_finder.h"

#include <algorithm>
#include <bit>

#include "core/engine/interior_plane.h"
#include "core/engine/state_planes.h"

namespace membrane {

PlaceFinder::PlaceFinder(const VoxelGrid& grid) : grid_(grid) {}

bool PlaceFinder::EnsurePlanes(const CancelToken* cancel) {
  const int64_t nv = grid_.size();
  if (interior_.bits() != nv) interior_ = InteriorPlane(grid_);
  FlatBitset* planes[] = {&out_, &boundary_soft_, &free_, &candidates_, &ok_, &covered_};
  for (FlatBitset* plane : planes) {
    if (cancel != nullptr && cancel->cancelled()) return false;
    plane->EnsureSize(nv);
  }
  for (int o = 0; o < 6; ++o) {
    if (cancel != nullptr && cancel->cancelled()) return false;
    anchors_[o].EnsureSize(nv);
    anchor_rows_[o].EnsureSize(nv);
  }
  return true;
}

std::optional<std::vector<int64_t>> PlaceFinder::Snapshot(int n, const CancelToken* cancel) {
  auto cancelled = [cancel] { return cancel != nullptr && cancel->cancelled(); };
  if (!EnsurePlanes(cancel)) return std::nullopt;
  n_ = n;
  const auto st = grid_.strides();
  FlatBitset& out = out_;
  FlatBitset& bs = boundary_soft_;
  FillStatePlane(grid_.states(), StatePredicate::kOutside, out);
  FillStatePlane(grid_.states(), StatePredicate::kBoundarySoft, bs);
  if (cancelled()) return std::nullopt;
  FlatBitset& free_cells = free_;  // outside or boundary soft, off the border
  free_cells = out;
  free_cells.Or(bs);
  free_cells.And(interior_);

  FlatBitset& candidates = candidates_;
  FlatBitset& ok = ok_;
  FlatBitset& covered = covered_;
  candidates.clear_all();
  for (int o = 0; o < 6; ++o) {
    if (cancelled()) return std::nullopt;
    const Orientation& orient = kOrientations[o];
    // ok[i] = free[i] & out[i - sign * stride_a]: the back side is outside.
    ok.AssignShifted(out, orient.sign * st[orient.axis]);
    ok.And(free_cells);
    FlatBitset& e = anchors_[o];
    e = ok;
    e.ErodeRun(n, st[orient.u_axis()]);
    e.ErodeRun(n, st[orient.v_axis()]);
    FlatBitset& dc = anchor_rows_[o];
    dc = e;
    dc.DilateRun(n, st[orient.v_axis()]);
    covered = dc;
    covered.DilateRun(n, st[orient.u_axis()]);
    covered.And(bs);
    candidates.Or(covered);
  }
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

std::optional<Plate> PlaceFinder::PlaceFor(int64_t index) const {
  const Coord c = grid_.CoordOf(index);
  for (int o = 0; o < 6; ++o) {
    const Orientation& orient = kOrientations[o];
    const int k = c[orient.axis], u = c[orient.u_axis()], v = c[orient.v_axis()];
    for (int u0 = std::max(u - n_ + 1, 0); u0 <= u; ++u0) {
      if (!anchor_rows_[o].test(grid_.Index(PlateCell(orient, k, u0, v)))) continue;
      for (int v0 = std::max(v - n_ + 1, 0); v0 <= v; ++v0) {
        if (anchors_[o].test(grid_.Index(PlateCell(orient, k, u0, v0)))) {
          return Plate{o, k, u0, v0};
        }
      }
    }
  }
  return std::nullopt;
}

}  // namespace membrane
