#include "core/pipeline/surface_builder.h"

#include <utility>

#include "absl/status/status.h"
#include "absl/strings/str_cat.h"
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

absl::StatusOr<BuiltSurface> BuildSurface(const VoxelGrid& membrane, const PointCloud& cloud,
                                          SurfaceKind kind, const PositionGrid& grid,
                                          const CancelToken& cancel, int threads,
                                          ProgressRange progress) {
  BuiltSurface built;
  if (kind == SurfaceKind::kCuberille) {
    built.mesh = Cuberille(membrane);
    for (Point3f& p : built.mesh.vertices) p = grid.Snap(p);
    progress.Done();
    return built;
  }
  // The fit writes every position on the grid itself.
  SmoothSurfaceOptions options;
  options.fit_options.output_grid = grid;
  options.fit_options.threads = threads;
  SmoothSurfaceStats stats;
  absl::StatusOr<TriangleMesh> mesh =
      SmoothSurface(membrane, cloud.points, options, &stats, cancel, progress);
  if (!mesh.ok()) return mesh.status();
  built.mesh = *std::move(mesh);
  built.hole_caps = stats.caps;
  if (stats.fit.crossings_known) built.crossings = std::move(stats.fit.crossings);
  return built;
}

}  // namespace membrane
