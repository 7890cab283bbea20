// Plates (paper section 4.1; algorithm-notes 4): n x n squares of voxels parallel to a
// coordinate plane, with an orientation that points into the solid.
#ifndef MEMBRANE_CORE_ENGINE_PLATE_H_
#define MEMBRANE_CORE_ENGINE_PLATE_H_

#include <cstdint>

#include "core/engine/voxel_grid.h"

namespace membrane {

// Orientation (a, sg): `axis` a is the plate's normal, `sign` +1/-1 the front direction.
// The in-plane axes are b = (a+1) % 3 ("u") and c = (a+2) % 3 ("v").
struct Orientation {
  int axis = 0;
  int sign = 1;
  int u_axis() const { return (axis + 1) % 3; }
  int v_axis() const { return (axis + 2) % 3; }
};

// The six orientations in the order places are searched: x+, x-, y+, y-, z+, z-.
inline constexpr Orientation kOrientations[6] = {{0, 1}, {0, -1}, {1, 1}, {1, -1}, {2, 1}, {2, -1}};

// A plate of size n: cells {layer} x [u0, u0+n) x [v0, v0+n) in (a, b, c) coordinates.
// Its back side is the same square at layer - sign, its front side at layer + sign.
struct Plate {
  int orientation = 0;  // index into kOrientations
  int layer = 0;
  int u0 = 0;
  int v0 = 0;
};

// Voxel coordinates of cell (u, v) of layer `layer` in orientation `o`.
inline Coord PlateCell(const Orientation& o, int layer, int u, int v) {
  Coord c;
  c[o.axis] = layer;
  c[o.u_axis()] = u;
  c[o.v_axis()] = v;
  return c;
}

}  // namespace membrane

#endif  // MEMBRANE_CORE_ENGINE_PLATE_H_
