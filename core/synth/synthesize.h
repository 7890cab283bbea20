// Synthetic point clouds with a known topology: the public entry point of membrane_synth,
// used by the engine's tests and by `membrane synth SHAPE -o OUT ...`.
//
// Shapes (model units, centred near the origin, about 2 across; smooth surfaces are sampled
// uniformly by area before the density ramp):
//   sphere         the unit sphere;
//   two-spheres    two unit spheres 0.3 apart whose axis silhouettes overlap
//                  (sphere_surfaces.h);
//   torus          R = 0.7, r = 0.45, axis (1,1,1)/sqrt(3): its hole shows in no axis view
//                  (torus_surface.h explains why not R = 1, r = 0.4);
//   capped-sphere  the unit sphere without points in the 25-degree cap around +z;
//   cube-pinholes  a one-voxel-thick cube shell with two pinholes, for one voxel size
//                  (cube_pinholes.h: voxelize it exactly as documented there).
#ifndef MEMBRANE_CORE_SYNTH_SYNTHESIZE_H_
#define MEMBRANE_CORE_SYNTH_SYNTHESIZE_H_

#include "absl/status/statusor.h"
#include "core/geometry/point_cloud.h"
#include "core/synth/shape_catalog.h"
#include "core/synth/synth_options.h"

namespace membrane {

// A cloud of exactly options.points points of options.shape; the same options always give the
// same cloud. Holes, density ratio and noise apply to the smooth shapes (see SynthLayout and
// SampleSmoothShape for the exact model). InvalidArgument, naming the field and its allowed
// range, for an option out of range (ValidateSynthOptions) or not supported by the shape
// (cube-pinholes: CubePinholesGridFor, SynthesizeCubePinholes); for an unknown shape, the
// message lists SynthShapeNames().
absl::StatusOr<PointCloud> SynthesizeShape(const SynthOptions& options);

}  // namespace membrane

#endif  // MEMBRANE_CORE_SYNTH_SYNTHESIZE_H_
