// The sphere-based shapes: sphere, two-spheres and capped-sphere.
#ifndef MEMBRANE_CORE_SYNTH_SPHERE_SURFACES_H_
#define MEMBRANE_CORE_SYNTH_SPHERE_SURFACES_H_

#include <array>
#include <memory>

#include "core/synth/surface_sampler.h"
#include "core/geometry/vec3.h"

namespace membrane {

// two-spheres: two radius-1 spheres whose centres are this far apart, so the gap between the
// surfaces is 0.3 ...
inline constexpr double kTwoSpheresCentreDistance = 2.3;
// ... placed symmetrically about the origin along the (1, 1, 1) diagonal: the centres' offset
// projects to 2.3 * sqrt(2/3) = 1.88 < 2 on every axis plane, so every axis-aligned silhouette
// of one sphere overlaps the other's, while the spheres stay 0.3 apart.
std::array<Vec3d, 2> TwoSpheresCentres();

// capped-sphere: the unit sphere without the cap of this half-angle around +z. Its rim is a
// circle of diameter 2 sin(25 deg) = 0.85, smaller than a first shrink plate.
inline constexpr double kCapHalfAngleDegrees = 25.0;
// cos(kCapHalfAngleDegrees): capped-sphere has no point with z above it (before noise).
double CappedSphereMaxZ();

// Unit sphere at the origin.
std::unique_ptr<SurfaceSampler> MakeUnitSphere();
// Two unit spheres at TwoSpheresCentres(), each drawn with probability 1/2 (equal areas).
std::unique_ptr<SurfaceSampler> MakeTwoSpheres();
// Unit sphere at the origin minus the cap z > CappedSphereMaxZ(). ExtentAlong reports the full
// sphere's extent, [-1, 1].
std::unique_ptr<SurfaceSampler> MakeCappedSphere();

}  // namespace membrane

#endif  // MEMBRANE_CORE_SYNTH_SPHERE_SURFACES_H_
