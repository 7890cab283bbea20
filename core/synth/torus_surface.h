// The `torus` shape: a ring torus tilted so that no axis-aligned view shows its hole.
//
// Seen along a unit vector e, the torus's centre circle projects to an ellipse with semi-axes
// R and R |a.e| (a = torus axis), and the solid's silhouette is that ellipse thickened by r. The
// ellipse's inside is all within R |a.e| of the ellipse, so the hole is hidden iff
// R |a.e| < r. Some axis always has |a.e| >= 1/sqrt(3) (the components of a unit vector), so
// the hole can hide from x, y and z at once only if r / R > 1/sqrt(3) = 0.577, and best with
// a = (1, 1, 1)/sqrt(3). Hence r / R = 0.64 here rather than a thinner tube: the hidden
// margin is r - R/sqrt(3) = 0.046, and the hole through the ring is 2 (R - r) = 0.5 wide.
#ifndef MEMBRANE_CORE_SYNTH_TORUS_SURFACE_H_
#define MEMBRANE_CORE_SYNTH_TORUS_SURFACE_H_

#include <memory>

#include "core/synth/surface_sampler.h"
#include "core/geometry/vec3.h"

namespace membrane {

// Radius of the centre circle and of the tube, model units; the outer diameter is 2.3.
inline constexpr double kTorusMajorRadius = 0.7;
inline constexpr double kTorusMinorRadius = 0.45;

// Unit axis of the torus, (1, 1, 1)/sqrt(3); the torus is centred at the origin.
Vec3d TorusAxis();

// The tilted torus, sampled uniformly by area.
std::unique_ptr<SurfaceSampler> MakeTiltedTorus();

}  // namespace membrane

#endif  // MEMBRANE_CORE_SYNTH_TORUS_SURFACE_H_
