// A concave corner under a data hole: where the band of surface around a hole shows two
// surfaces meeting (a belly meeting a leg), a smooth cap from the rim spans the corner as a
// fillet outside it. Each side's surface carried on into the hole, the two meet in a crease:
// the cap is the boundary of the union of the two sides' solids there (hole_caps.h,
// docs/surface-decisions.md "Caps over a concave corner").
#ifndef MEMBRANE_CORE_MESH_CORNER_CREASE_H_
#define MEMBRANE_CORE_MESH_CORNER_CREASE_H_

#include "absl/types/span.h"
#include "core/geometry/vec3.h"

namespace membrane {

// Lengths in the band's units.
struct CornerCreaseOptions {
  // Directions around a cap position (in the plane square to the axis the hole is seen
  // along), an even count: the band on either side of the position is read in opposite
  // sectors (at most 360).
  int sectors = 12;
  // Each sector's side: the plane through the mean of its this many band members nearest to
  // the position, square to the mean of their normals.
  int per_sector = 3;
  // Two opposite sides are two surfaces when their normals lie at least this far apart
  // (degrees).
  double min_angle = 45.0;
  // A side is flat or convex: the mean of all its sector's members lies at most this far
  // outside its plane. A smooth concave surface curves away outside its tangent planes, and
  // the smooth cap already follows it.
  double flat_tolerance = 1.0;
  // The largest move of a position.
  double max_move = 12.0;
  // The band is kept in cubic cells of reach / 4 (or more, at most about 64 along its box):
  // the cells within `reach` of a position's (along each axis) are read member by member,
  // each farther cell as one member at its members' mean position and normal, weighing their
  // count in its sector's mean. The cost a position is the band's arc near it and a cell for
  // each farther part, not the whole band (a 10M-point scan's caps hold 10^5 positions, their
  // bands 10^4 members).
  double reach = 64.0;
};

// Input: the band's positions and unit outward normals (the same count), `axis` a unit
// direction along which the hole is seen (the band's mean normal), `cap` positions.
// Effect: for each cap position, the band read in sectors around it (farther parts by cells,
// see `reach`), and for each pair of opposite sectors whose sides (CornerCreaseOptions) are
// flat or convex, lie min_angle apart and each outside the other's plane (a concave
// corner), a position outside both planes (a fillet spanning the corner, outside the union
// of the two solids) reaches the union's boundary moving inward along the two normals' mean,
// up to the first plane. The position takes the longest such move over the pairs (at most
// max_move); positions with none stay (a convex or flat span lies inside a side). Returns
// how many moved. The positions are shared out over `threads` (<= 1: the
// calling thread); the result is the same for any count.
int CreaseToCorner(absl::Span<const Vec3d> positions, absl::Span<const Vec3d> normals,
                   const Vec3d& axis, const CornerCreaseOptions& options,
                   absl::Span<Vec3d> cap, int threads = 1);

}  // namespace membrane

#endif  // MEMBRANE_CORE_MESH_CORNER_CREASE_H_
