// The place of a candidate voxel (paper section 4.3, FindContractionPlace): the one search
// both the dense snapshot (place_finder.cc, on its packed anchors) and the local one
// (local_snapshot.cc, on a brick's box) run, so that the two give the same plate.
#ifndef MEMBRANE_CORE_ENGINE_FIRST_ANCHORED_PLATE_H_
#define MEMBRANE_CORE_ENGINE_FIRST_ANCHORED_PLATE_H_

#include <algorithm>
#include <optional>

#include "core/engine/plate.h"
#include "core/engine/voxel_grid.h"

namespace membrane {

// The plate of size n >= 1 the paper's list scan takes for the voxel at `c` (grid
// coordinates): the first orientation in kOrientations order, then the smallest u0, then the
// smallest v0, whose anchor (lowest corner, PlateCell(orient, layer, u0, v0)) is set.
// nullopt when no anchor covers `c`.
//   anchor(o, cell) -> bool: whether a fitting plate of orientation o has its lowest corner at
//     `cell` (grid coordinates, every cell within n - 1 below `c` along u and v, off the grid's
//     low border).
//   row(o, cell) -> bool: false only when anchor(o, PlateCell(orient, layer, u0, v0)) is false
//     for every v0 in [v - n + 1, v], where cell = PlateCell(orient, layer, u0, v); a row test
//     that always returns true gives the same plate with n times more anchor tests. It is asked
//     once per (orientation, u0), before that row's anchors.
template <typename Anchor, typename Row>
std::optional<Plate> FirstAnchoredPlate(const Coord& c, int n, const Anchor& anchor,
                                        const Row& row) {
  for (int o = 0; o < 6; ++o) {
    const Orientation& orient = kOrientations[o];
    const int layer = c[orient.axis], u = c[orient.u_axis()], v = c[orient.v_axis()];
    for (int u0 = std::max(u - n + 1, 0); u0 <= u; ++u0) {
      if (!row(o, PlateCell(orient, layer, u0, v))) continue;
      for (int v0 = std::max(v - n + 1, 0); v0 <= v; ++v0) {
        if (anchor(o, PlateCell(orient, layer, u0, v0))) return Plate{o, layer, u0, v0};
      }
    }
  }
  return std::nullopt;
}

}  // namespace membrane

#endif  // MEMBRANE_CORE_ENGINE_FIRST_ANCHORED_PLATE_H_
