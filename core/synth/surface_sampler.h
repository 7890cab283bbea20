// The interface of the smooth shapes: area-uniform sampling and extent along a direction.
#ifndef MEMBRANE_CORE_SYNTH_SURFACE_SAMPLER_H_
#define MEMBRANE_CORE_SYNTH_SURFACE_SAMPLER_H_

#include <random>

#include "core/geometry/vec3.h"

namespace membrane {

// A point on a surface with its outward unit normal (model units).
struct SurfaceSample {
  Vec3d position{};
  Vec3d normal{};
};

// A closed interval [lo, hi] of a coordinate along some direction, model units.
struct Interval {
  double lo = 0.0;
  double hi = 0.0;
};

class SurfaceSampler {
 public:
  virtual ~SurfaceSampler() = default;
  // One point drawn uniformly by area over the surface.
  virtual SurfaceSample Sample(std::mt19937_64& rng) const = 0;
  // Range of Dot(p, direction) over the surface (or a documented superset); `direction` is a
  // unit vector.
  virtual Interval ExtentAlong(const Vec3d& direction) const = 0;
};

}  // namespace membrane

#endif  // MEMBRANE_CORE_SYNTH_SURFACE_SAMPLER_H_
