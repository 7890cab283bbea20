#include "core/pipeline/surface_builder.h"

#include <algorithm>
#include <cmath>

#include "absl/status/status.h"
#include "absl/strings/str_cat.h"
#include "core/mesh/cancel_fn.h"
#include "core/mesh/cuberille.h"
#include "core/mesh/smooth_surface.h"

namespace membrane {

absl::StatusOr<SurfaceKind> ParseSurfaceKind(absl::string_view name) {
  if (name == "smooth") return SurfaceKind::kSmooth;
  if (name == "cuberille") return SurfaceKind::kCuberille;
  return absl::InvalidArgumentError(
      absl::StrCat("--surface '", name, "' is not one of: smooth, cuberille"));
}

const char* SurfaceKindName(SurfaceKind kind) {
  return kind == SurfaceKind::kSmooth ? "smooth" : "cuberille";
}

absl::StatusOr<TriangleMesh> BuildSurface(const VoxelGrid& membrane, const PointCloud& cloud,
                                          SurfaceKind kind, const PositionGrid& grid,
                                          const CancelToken* cancel) {
  absl::StatusOr<TriangleMesh> mesh;
  if (kind == SurfaceKind::kCuberille) {
    mesh = Cuberille(membrane);
  } else {
    const CancelFn cancelled = [cancel] { return cancel != nullptr && cancel->cancelled(); };
    SmoothSurfaceOptions options;
    options.fit_options.output_grid = grid;
    mesh = SmoothSurface(membrane, cloud.points, options, nullptr, cancelled);
  }
  // The fit's vertices are on the grid already (snapping is idempotent).
  if (mesh.ok() && !grid.lossless())
    for (Point3f& p : mesh->vertices) p = grid.Snap(p);
  return mesh;
}

PositionGrid OutputGrid(const VoxelGrid& membrane, int bits) {
  PositionGrid grid;
  grid.bits = bits;
  const double side =
      membrane.voxel_size() * std::max({membrane.dim(0), membrane.dim(1), membrane.dim(2)});
  // Rounded outward to values Draco's options keep (DecimalSafeBound), so that the grid the
  // surface is snapped to is the grid the file is decoded on.
  double far_side = 0;
  for (int axis = 0; axis < 3; ++axis) {
    grid.box.origin[axis] = DecimalSafeBound(membrane.origin()[axis], /*lower=*/true);
    far_side = std::max(far_side, membrane.origin()[axis] + side - grid.box.origin[axis]);
  }
  grid.box.range = DecimalSafeBound(far_side * (1 + 1e-6), /*lower=*/false);
  return grid;
}

}  // namespace membrane
