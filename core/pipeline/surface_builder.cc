#include "core/pipeline/surface_builder.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

#include "absl/status/status.h"
#include "absl/strings/str_cat.h"
#include "core/base/parallel_tasks.h"
#include "core/mesh/cuberille.h"
#include "core/mesh/mesh_check.h"
#include "core/mesh/self_intersection.h"
#include "core/mesh/smooth_surface.h"

namespace membrane {
namespace {

// Faces per task of KnownBroken's degenerate-face pass.
constexpr size_t kFacesPerBlock = size_t{1} << 16;

// One flag per vertex of a cuberille of `membrane`: set for the vertices that are not lattice
// corners (split, edge midpoints, chamfers: 0.2 voxel or more off the lattice on some axis).
std::vector<char> SplitVertices(const TriangleMesh& cuberille, const VoxelGrid& membrane) {
  std::vector<char> split(cuberille.vertices.size(), 0);
  const std::array<double, 3>& origin = membrane.origin();
  for (size_t v = 0; v < split.size(); ++v) {
    for (int axis = 0; axis < 3; ++axis) {
      const double q = (cuberille.vertices[v][axis] - origin[axis]) / membrane.voxel_size();
      if (std::abs(q - std::round(q)) > 0.05) split[v] = 1;
    }
  }
  return split;
}

// Whether a face around a split vertex crosses another face of the snapped `cuberille`. The
// lattice corners keep their order on any grid finer than a voxel, so the faces between them
// stay apart; only the split sheets, moved apart by a fraction of a voxel, can meet. A few faces
// in a thousand: a small share of the check's whole search.
bool SplitFacesCross(const TriangleMesh& cuberille, const std::vector<char>& split, int threads) {
  std::vector<char> near(cuberille.faces.size(), 0);
  bool any = false;
  for (size_t f = 0; f < near.size(); ++f) {
    for (const int32_t v : cuberille.faces[f]) near[f] |= split[v];
    any = any || near[f];
  }
  return any && !FindIntersectingFacesNear(cuberille, near, threads).empty();
}

BuiltSurface CuberilleSurface(const VoxelGrid& membrane, const PositionGrid& grid, int threads,
                              ProgressRange progress) {
  BuiltSurface built;
  built.mesh = Cuberille(membrane);
  const std::vector<char> split = SplitVertices(built.mesh, membrane);
  for (Point3f& p : built.mesh.vertices) p = grid.Snap(p);
  built.split_crossings = !grid.lossless() && SplitFacesCross(built.mesh, split, threads);
  progress.Done();
  return built;
}

}  // namespace

absl::StatusOr<SurfaceKind> ParseSurfaceKind(absl::string_view name) {
  if (name == "smooth") return SurfaceKind::kSmooth;
  if (name == "cuberille") return SurfaceKind::kCuberille;
  return absl::InvalidArgumentError(
      absl::StrCat("--surface '", name, "' is not one of: smooth, cuberille"));
}

const char* SurfaceKindName(SurfaceKind kind) {
  return kind == SurfaceKind::kSmooth ? "smooth" : "cuberille";
}

bool KnownBroken(const BuiltSurface& surface, int threads) {
  if (surface.split_crossings) return true;
  if (surface.crossings && !surface.crossings->empty()) return true;
  // On the threads: a pass over every face (15M at 10M points) between the surface and the
  // check, with nothing else to run beside it. A block stops at its first degenerate face, and
  // every block stops once one has found one.
  const std::vector<std::array<int32_t, 3>>& faces = surface.mesh.faces;
  const size_t blocks = (faces.size() + kFacesPerBlock - 1) / kFacesPerBlock;
  std::atomic<bool> degenerate{false};
  RunTasks(threads, static_cast<int64_t>(blocks), [&](int, int64_t block) {
    const size_t begin = static_cast<size_t>(block) * kFacesPerBlock;
    const size_t end = std::min(faces.size(), begin + kFacesPerBlock);
    for (size_t f = begin; f < end && !degenerate.load(std::memory_order_relaxed); ++f) {
      if (IsDegenerateFace(surface.mesh, faces[f])) {
        degenerate.store(true, std::memory_order_relaxed);
      }
    }
  });
  return degenerate.load();
}

absl::StatusOr<BuiltSurface> BuildSurface(const VoxelGrid& membrane, const PointCloud& cloud,
                                          SurfaceKind kind, const PositionGrid& grid,
                                          const CancelToken& cancel, int threads,
                                          ProgressRange progress, double point_noise) {
  // The cuberille only reads the membrane: no copy.
  if (kind == SurfaceKind::kCuberille) return CuberilleSurface(membrane, grid, threads, progress);
  return BuildSurface(VoxelGrid(membrane), cloud, kind, grid, cancel, threads, progress,
                      point_noise);
}

absl::StatusOr<BuiltSurface> BuildSurface(VoxelGrid&& given, const PointCloud& cloud,
                                          SurfaceKind kind, const PositionGrid& grid,
                                          const CancelToken& cancel, int threads,
                                          ProgressRange progress, double point_noise) {
  VoxelGrid membrane = std::move(given);
  given = VoxelGrid();
  if (kind == SurfaceKind::kCuberille) return CuberilleSurface(membrane, grid, threads, progress);
  BuiltSurface built;
  // The fit writes every position on the grid itself.
  SmoothSurfaceOptions options;
  options.fit_options.output_grid = grid;
  options.fit_options.threads = threads;
  if (point_noise > 0 && membrane.voxel_size() > 0)
    options.fit_options.crease_limits.noise = point_noise / membrane.voxel_size();
  SmoothSurfaceStats stats;
  absl::StatusOr<TriangleMesh> mesh =
      SmoothSurface(std::move(membrane), cloud.points, options, &stats, cancel, progress);
  if (!mesh.ok()) return mesh.status();
  built.mesh = *std::move(mesh);
  built.hole_caps = stats.caps;
  built.steps = stats.seconds;
  built.fit = FitTargetCounts{stats.fit.quadric_targets, stats.fit.plane_targets,
                              stats.fit.crease_targets, stats.fit.crease_line_targets,
                              stats.fit.umbrella_targets};
  if (stats.fit.crossings_known) built.crossings = std::move(stats.fit.crossings);
  return built;
}

}  // namespace membrane
