// The closed form's fixed point on bit-planes (fast-shrink.md section 4), on any box of
// voxels given its free cells and outside voxels. closed_form_generation.h builds the planes
// from the grid's states, then applies and checks the result.
#ifndef MEMBRANE_CORE_ENGINE_CLOSED_FORM_SWEEPS_H_
#define MEMBRANE_CORE_ENGINE_CLOSED_FORM_SWEEPS_H_

#include <array>
#include <cstdint>
#include <optional>

#include "core/base/cancel_token.h"
#include "core/engine/flat_bitset.h"

namespace membrane {

// A box of voxels on the flat index x + nx * (y + ny * z).
struct PlaneBox {
  std::array<int, 3> dims = {0, 0, 0};
  std::array<int64_t, 3> strides = {1, 0, 0};
  int64_t size() const { return static_cast<int64_t>(dims[0]) * dims[1] * dims[2]; }
};

// A box of `dims` voxels with its strides.
PlaneBox MakePlaneBox(const std::array<int, 3>& dims);

// The planes the sweeps work in, all of the box's size and distinct: squares[a] holds the
// anchors of all-free n x n squares across plate axis a (FreeSquares), the others are
// overwritten (`back` is also the spreads' second scratch once both fronts have read it).
struct SweepPlanes {
  FlatBitset* squares[3];
  FlatBitset* back;
  FlatBitset* reach;
  FlatBitset* reach_back;
  FlatBitset* scratch;
};

// squares[a] = anchors of the n x n squares of set `free_cells` across axis a (both signs of
// the axis share them). `free_cells` must be clear on the box's outermost layer, so that no
// square wraps around a row. squares[2] serves as a scratch plane before it is written;
// `scratch` is overwritten.
void FreeSquares(const FlatBitset& free_cells, int n, const PlaneBox& box,
                 FlatBitset* const squares[3], FlatBitset& scratch);

// Adds to `out` (the outside voxels) until it is the least fixed point of "a plate of n x n
// cells of its square planes whose back square is all in `out` joins `out`": rounds of the
// three axes, both fronts at once, at most 64 rounds. Returns the rounds run, or nullopt when
// `cancel` fired (`out` is then part of the way there).
std::optional<int> SweepToFixedPoint(FlatBitset& out, int n, const PlaneBox& box,
                                     const SweepPlanes& planes, const CancelToken& cancel);

}  // namespace membrane

#endif  // MEMBRANE_CORE_ENGINE_CLOSED_FORM_SWEEPS_H_
