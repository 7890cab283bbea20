#include "core/synth/smooth_shape_cloud.h"

#include "core/synth/density_ramp.h"
#include "core/synth/surface_holes.h"
#include "core/synth/synth_random.h"

namespace membrane {

PointCloud SampleSmoothShape(const SurfaceSampler& surface, const SynthLayout& layout,
                             const SynthOptions& options) {
  std::mt19937_64 rng = SeededStream(options.seed, kSampleStream);
  const DensityRamp ramp(layout.density_direction, surface.ExtentAlong(layout.density_direction),
                         options.density_ratio);
  const SurfaceHoles holes(layout.hole_centres);

  PointCloud cloud;
  cloud.points.reserve(static_cast<size_t>(options.points));
  // Rejection sampling keeps the result area-uniform times the ramp. It terminates quickly:
  // the ramp keeps >= 1/1000 everywhere and about 1/5 on average at the largest ratio, and
  // 100 holes of area ~pi 0.15^2 remove at most about 60% of the smallest shape's area.
  while (static_cast<int64_t>(cloud.points.size()) < options.points) {
    const SurfaceSample s = surface.Sample(rng);
    if (Uniform01(rng) >= ramp.Acceptance(s.position)) continue;
    if (holes.Removes(s.position)) continue;
    Vec3d p = s.position;
    // Drawn only when asked for, so noise-free clouds skip the Box-Muller cost.
    if (options.noise > 0.0) p = p + options.noise * StandardNormal(rng) * s.normal;
    cloud.points.push_back(
        {static_cast<float>(p[0]), static_cast<float>(p[1]), static_cast<float>(p[2])});
  }
  return cloud;
}

}  // namespace membrane
