// Holes: circular patches of a surface left without points.
#ifndef MEMBRANE_CORE_SYNTH_SURFACE_HOLES_H_
#define MEMBRANE_CORE_SYNTH_SURFACE_HOLES_H_

#include <vector>

#include "core/geometry/vec3.h"

namespace membrane {

// Radius of every hole, model units: the patch is the surface inside a ball of this radius
// around a centre on the surface (a disc about 0.3 across).
inline constexpr double kHoleRadius = 0.15;

class SurfaceHoles {
 public:
  // `centres`: points on the surface, model units; may be empty.
  explicit SurfaceHoles(std::vector<Vec3d> centres);

  // True when `p` (model units, before noise) lies within kHoleRadius of some centre.
  bool Removes(const Vec3d& p) const;

 private:
  std::vector<Vec3d> centres_;  // sorted by x, so a query scans only a slab of width 2 radii
};

}  // namespace membrane

#endif  // MEMBRANE_CORE_SYNTH_SURFACE_HOLES_H_
