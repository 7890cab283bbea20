#include "core/synth/smooth_shapes.h"

#include "absl/status/status.h"
#include "absl/strings/str_cat.h"
#include "core/synth/shape_catalog.h"
#include "core/synth/sphere_surfaces.h"
#include "core/synth/torus_surface.h"

namespace membrane {

absl::StatusOr<std::unique_ptr<SurfaceSampler>> MakeSmoothShape(const std::string& shape) {
  if (shape == kShapeSphere) return MakeUnitSphere();
  if (shape == kShapeTwoSpheres) return MakeTwoSpheres();
  if (shape == kShapeTorus) return MakeTiltedTorus();
  if (shape == kShapeCappedSphere) return MakeCappedSphere();
  return absl::InvalidArgumentError(
      absl::StrCat("shape '", shape, "' is not a smooth shape (sphere, two-spheres, torus, ",
                   "capped-sphere)"));
}

}  // namespace membrane
