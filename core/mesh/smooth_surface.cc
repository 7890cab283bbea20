#include "core/mesh/smooth_surface.h"

#include <chrono>
#include <optional>
#include <utility>

#include "absl/status/status.h"
#include "core/mesh/cave_filling.h"
#include "core/mesh/diagonal_bridging.h"
#include "core/mesh/loose_sheets.h"
#include "core/mesh/point_row_grid.h"
#include "core/mesh/surface_nets.h"

namespace membrane {
namespace {

// Shares of the surface's progress (about a tenth each on a 200^3 ball; the fit is the rest).
constexpr double kPrepareShare = 0.1;
constexpr double kNetsEnd = 0.2;

double SecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

absl::StatusOr<TriangleMesh> SmoothSurface(const VoxelGrid& membrane,
                                           absl::Span<const Point3f> points,
                                           const SmoothSurfaceOptions& options,
                                           SmoothSurfaceStats* stats, const CancelToken& cancel,
                                           ProgressRange progress) {
  // The membrane and its reported topology stay as they are: the clean-up is for the surface.
  return SmoothSurface(VoxelGrid(membrane), points, options, stats, cancel, progress);
}

absl::StatusOr<TriangleMesh> SmoothSurface(VoxelGrid&& membrane,
                                           absl::Span<const Point3f> points,
                                           const SmoothSurfaceOptions& options,
                                           SmoothSurfaceStats* stats, const CancelToken& cancel,
                                           ProgressRange progress) {
  SmoothSurfaceStats local;
  SmoothSurfaceStats& s = stats ? *stats : local;
  s = SmoothSurfaceStats{};
  auto start = std::chrono::steady_clock::now();
  // Taken over, so that it is freed on every return.
  VoxelGrid grid = std::move(membrane);
  membrane = VoxelGrid();
  const double voxel_size = grid.voxel_size();
  // Progress: the clean-up's three steps, the nets, then the fit (most of the time).
  const ProgressRange prepare = progress.Part(0, kPrepareShare);
  prepare.Begin(3);
  // Loose sheets go first so that cave filling cannot thicken a sheet into something kept.
  if (options.remove_loose_sheets) s.loose_sheet_voxels = RemoveLooseSheets(grid, options.fit_options.threads);
  prepare.Add(1);
  if (cancel.cancelled()) return absl::CancelledError("surface cancelled");
  if (options.fill_caves) s.cave_voxels = FillCaves(grid, options.fit_options.threads);
  prepare.Add(1);
  if (cancel.cancelled()) return absl::CancelledError("surface cancelled");
  if (options.bridging_scans > 0) {
    const BridgingResult bridging =
        BridgeDiagonalContacts(grid, options.bridging_scans, options.fit_options.threads);
    s.bridges = bridging.added;
    s.corner_contacts_left = bridging.remaining;
  }
  prepare.Add(1);
  s.seconds.prepare = SecondsSince(start);
  if (cancel.cancelled()) return absl::CancelledError("surface cancelled");

  start = std::chrono::steady_clock::now();
  if (!options.fit) {
    TriangleMesh mesh = SurfaceNets(grid);
    s.seconds.nets = SecondsSince(start);
    progress.Part(kPrepareShare, 1).Done();
    return mesh;
  }
  // The fit's first pass searches the whole mesh for crossings anyway: it also does the
  // surface nets' repair (toward the same fallback).
  UnrepairedSurfaceNets nets = SurfaceNetsBeforeRepair(grid, options.fit_options.threads);
  // The cleaned grid has given its mesh: the caps and the fit read the mesh and the points,
  // and a byte a voxel is most of what the surface holds on a large grid (2.2 GB at 10M points).
  grid = VoxelGrid();
  s.seconds.nets = SecondsSince(start);
  progress.Part(kPrepareShare, kNetsEnd).Done();

  start = std::chrono::steady_clock::now();
  // One index of the points, cells of the gap radius, for the caps' gap search and, with the
  // fit's search radius the same, a dense cloud's means in the fit: each was a pass over every
  // point.
  const int threads = options.fit_options.threads;
  std::optional<PointRowGrid> points_grid;
  if (options.hole_caps.enabled && options.hole_caps.gap_radius > 0 && !points.empty() &&
      !nets.mesh.vertices.empty())
    points_grid.emplace(points, options.hole_caps.gap_radius * voxel_size, threads);
  // Before the fit: the fit then pulls the caps' rims onto the data and smooths the caps; its
  // final search covers the caps too.
  if (absl::Status capped =
          CapHoles(nets.mesh, voxel_size, points, options.hole_caps, &s.caps, cancel, threads,
                   points_grid ? &*points_grid : nullptr);
      !capped.ok())
    return capped;
  s.seconds.caps = SecondsSince(start);

  start = std::chrono::steady_clock::now();
  if (options.hole_caps.gap_radius != options.fit_options.search_radius) points_grid.reset();
  absl::StatusOr<FitStats> fit = FitToPoints(nets.mesh, voxel_size, points,
                                             options.fit_options, cancel, &nets.fallback,
                                             progress.Part(kNetsEnd, 1), std::move(points_grid));
  if (!fit.ok()) return fit.status();
  s.fit = *fit;
  s.seconds.fit = SecondsSince(start);
  return std::move(nets.mesh);
}

}  // namespace membrane
