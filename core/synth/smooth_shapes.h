// Maps the smooth shapes' names (every shape but cube-pinholes) to their surfaces.
#ifndef MEMBRANE_CORE_SYNTH_SMOOTH_SHAPES_H_
#define MEMBRANE_CORE_SYNTH_SMOOTH_SHAPES_H_

#include <memory>
#include <string>

#include "absl/status/statusor.h"
#include "core/synth/surface_sampler.h"

namespace membrane {

// The surface of `shape` (sphere, two-spheres, torus or capped-sphere). InvalidArgument naming
// the shape for any other name, cube-pinholes included (it is built per voxel, not sampled).
absl::StatusOr<std::unique_ptr<SurfaceSampler>> MakeSmoothShape(const std::string& shape);

}  // namespace membrane

#endif  // MEMBRANE_CORE_SYNTH_SMOOTH_SHAPES_H_
