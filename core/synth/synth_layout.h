// The random layout of a smooth shape's cloud: where density grows and where the holes are.
#ifndef MEMBRANE_CORE_SYNTH_SYNTH_LAYOUT_H_
#define MEMBRANE_CORE_SYNTH_SYNTH_LAYOUT_H_

#include <vector>

#include "absl/status/statusor.h"
#include "core/synth/surface_sampler.h"
#include "core/synth/synth_options.h"
#include "core/geometry/vec3.h"

namespace membrane {

// Drawn from the seed's layout stream only, so it depends on (shape, seed, holes) and not on
// the point count, density ratio or noise.
struct SynthLayout {
  // Unit vector along which the density grows (see DensityRamp); drawn even when
  // density_ratio is 1.
  Vec3d density_direction{0.0, 0.0, 1.0};
  // options.holes points on the surface, drawn uniformly by area; each is the centre of a hole
  // of radius kHoleRadius (holes may overlap).
  std::vector<Vec3d> hole_centres;
};

// The layout SynthesizeShape(options) uses for `surface` (the surface of options.shape).
SynthLayout DrawSynthLayout(const SurfaceSampler& surface, const SynthOptions& options);

// The layout of SynthesizeShape(options), for tests that need to know where the holes and the
// sparse side are. InvalidArgument for invalid options (see ValidateSynthOptions) or for a
// shape other than sphere, two-spheres, torus and capped-sphere (cube-pinholes has no random
// layout: see CubePinholesGridFor).
absl::StatusOr<SynthLayout> SynthesizeLayout(const SynthOptions& options);

}  // namespace membrane

#endif  // MEMBRANE_CORE_SYNTH_SYNTH_LAYOUT_H_
