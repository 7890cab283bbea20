// Point clouds of the smooth shapes: area-uniform samples, thinned, holed and noised.
#ifndef MEMBRANE_CORE_SYNTH_SMOOTH_SHAPE_CLOUD_H_
#define MEMBRANE_CORE_SYNTH_SMOOTH_SHAPE_CLOUD_H_

#include "core/geometry/point_cloud.h"
#include "core/synth/surface_sampler.h"
#include "core/synth/synth_layout.h"
#include "core/synth/synth_options.h"

namespace membrane {

// Exactly options.points points on `surface`: each is drawn uniformly by area (from the seed's
// sample stream), kept with the probability of the DensityRamp along
// layout.density_direction, dropped when it falls in a hole of layout.hole_centres, then moved
// along its normal by a Gaussian of standard deviation options.noise (model units).
// `options` must satisfy ValidateSynthOptions (the loop relies on the acceptance being
// bounded away from 0).
PointCloud SampleSmoothShape(const SurfaceSampler& surface, const SynthLayout& layout,
                             const SynthOptions& options);

}  // namespace membrane

#endif  // MEMBRANE_CORE_SYNTH_SMOOTH_SHAPE_CLOUD_H_
