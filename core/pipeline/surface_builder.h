// The surface step of `membrane reconstruct` (paper section 6): which surface to build from
// the final membrane, by the name given to --surface.
#ifndef MEMBRANE_CORE_PIPELINE_SURFACE_BUILDER_H_
#define MEMBRANE_CORE_PIPELINE_SURFACE_BUILDER_H_

#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "core/base/cancel_token.h"
#include "core/base/progress_meter.h"
#include "core/engine/voxel_grid.h"
#include "core/geometry/point_cloud.h"
#include "core/geometry/position_grid.h"
#include "core/geometry/triangle_mesh.h"
#include "core/mesh/hole_caps.h"
#include "core/mesh/output_grid.h"
#include "core/mesh/point_fitting.h"
#include "core/mesh/smooth_surface.h"

namespace membrane {

enum class SurfaceKind {
  kSmooth,     // surface nets fitted to the points (membrane-quality.md recipe 3)
  kCuberille,  // the voxel faces between the solid and the outside: exact but staircased
};

// "smooth" or "cuberille"; InvalidArgument "--surface 'x' is not one of: smooth, cuberille".
absl::StatusOr<SurfaceKind> ParseSurfaceKind(absl::string_view name);

// The --surface name of `kind`.
const char* SurfaceKindName(SurfaceKind kind);

// A surface, and what building it found out about it on the way.
struct BuiltSurface {
  TriangleMesh mesh;
  // Every pair of faces of `mesh` that intersect (as FindIntersectingFaces lists them), when
  // the build searched all of the mesh on exactly these positions: the smooth surface's fit
  // does. nullopt otherwise (cuberille): a mesh check must search.
  std::optional<std::vector<std::pair<int32_t, int32_t>>> crossings;
  HoleCapStats hole_caps;  // the smooth surface's caps over data holes (zero for cuberille)
  FitTargetCounts fit;     // the smooth surface's fit (zero for cuberille)
  SurfaceStepSeconds steps;  // the smooth surface's steps (zero for cuberille)
  // The cuberille's faces around its split vertices cross on the output grid: a grid about
  // as coarse as 0.2 voxel can snap a split vertex onto the sheet it was moved away from.
  bool split_crossings = false;
};

// Whether the mesh check is sure to find `surface` broken (self_intersections or
// degenerate_faces): the build found crossings (the fit's, or the cuberille's around its split
// vertices), or a face has no area (IsDegenerateFace). false says nothing: only the check can
// tell. The faces are read in blocks on `threads` (<= 1: the calling thread); the answer is the
// same for any count.
bool KnownBroken(const BuiltSurface& surface, int threads = 1);

// The closed, manifold, outward surface of `membrane` (a final DMS, its outer layer outside),
// vertices in model units on `grid` (OutputGrid's; lossless: float32); `cloud` is what the
// smooth surface is fitted to (SmoothSurface of core/mesh with its default options, fitting on
// `grid`; Cuberille ignores it and is snapped to `grid`). A coarse grid can flatten or cross
// faces: the caller's mesh check tells. Cancelled when `cancel` fires during the
// smooth surface. `threads` (<= 1: the calling thread) share the smooth surface's fit; the
// mesh does not depend on it. `progress` counts the smooth surface's work (SmoothSurface) and
// reaches its end with the surface.
// `point_noise` is the points' noise across their surface (PointNoise::sigma, model units; 0
// when unknown), which the fit's crease test discounts.
absl::StatusOr<BuiltSurface> BuildSurface(const VoxelGrid& membrane, const PointCloud& cloud,
                                          SurfaceKind kind, const PositionGrid& grid,
                                          const CancelToken& cancel, int threads = 1,
                                          ProgressRange progress = ProgressRange(),
                                          double point_noise = 0);

// The same from a membrane the caller gives up (the pipeline, which keeps it as runs): the
// smooth surface cleans it in place and frees it before the caps and the fit (SmoothSurface's
// consuming overload). `membrane` is left empty (a default VoxelGrid) whatever the outcome.
absl::StatusOr<BuiltSurface> BuildSurface(VoxelGrid&& membrane, const PointCloud& cloud,
                                          SurfaceKind kind, const PositionGrid& grid,
                                          const CancelToken& cancel, int threads = 1,
                                          ProgressRange progress = ProgressRange(),
                                          double point_noise = 0);

}  // namespace membrane

#endif  // MEMBRANE_CORE_PIPELINE_SURFACE_BUILDER_H_
