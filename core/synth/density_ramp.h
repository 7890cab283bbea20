// Density modulation: keeps a surface point with a probability that grows along a direction.
#ifndef MEMBRANE_CORE_SYNTH_DENSITY_RAMP_H_
#define MEMBRANE_CORE_SYNTH_DENSITY_RAMP_H_

#include "core/synth/surface_sampler.h"
#include "core/geometry/vec3.h"

namespace membrane {

// With s the position of Dot(p, direction) within the shape's extent (0 at its low end, 1 at
// its high end), the acceptance is 1/ratio for s <= 0.1, 1 for s >= 0.9 and geometric in
// between: ratio^((s - 0.1) / 0.8 - 1). The flat ends make the surface density of the
// sparsest and densest tenths exactly 1/ratio and 1, so a measured tenth-to-tenth ratio
// equals `ratio` (a ramp through the whole extent would show only part of it).
class DensityRamp {
 public:
  // `direction`: unit vector; `extent`: range of Dot(p, direction) on the shape, lo < hi;
  // `ratio` >= 1 (1 accepts everything).
  DensityRamp(const Vec3d& direction, const Interval& extent, double ratio);

  // Probability in [1/ratio, 1] of keeping a sample at `p` (model units). Points outside the
  // extent get the acceptance of the nearer end.
  double Acceptance(const Vec3d& p) const;

 private:
  Vec3d direction_;
  Interval extent_;
  double log_ratio_;
};

}  // namespace membrane

#endif  // MEMBRANE_CORE_SYNTH_DENSITY_RAMP_H_
