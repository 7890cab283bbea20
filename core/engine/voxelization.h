// Voxelization of a point cloud (paper section 4.3, formula (1); algorithm-notes 1).
#ifndef MEMBRANE_CORE_ENGINE_VOXELIZATION_H_
#define MEMBRANE_CORE_ENGINE_VOXELIZATION_H_

#include <array>
#include <cstdint>
#include <optional>

#include "absl/status/statusor.h"
#include "absl/types/span.h"
#include "core/base/cancel_token.h"
#include "core/base/progress_meter.h"
#include "core/engine/voxel_grid.h"
#include "core/geometry/point_cloud.h"

namespace membrane {

struct VoxelizeOptions {
  // Voxel edge length l in model units; 0 estimates it with the paper's formula (1).
  double voxel_size = 0.0;
  // Largest grid (voxels, padding included) that may be allocated; 0: no cap in voxels. The
  // pipeline's memory estimates (core/pipeline/memory_estimate.h) are what refuses a grid by
  // default: a cap in voxels refuses what a dense grid would need, not what would not fit.
  int64_t voxel_budget = 0;
  // Threads for the distinct-point count, the initial membrane's planes and the points' voxels
  // (RunTasks); the grid and the counts are the same for any number.
  int threads = 1;
  // CheckedBounds of the same points, when the caller has them already (the pipeline's grid
  // planning, PlanGrid): Voxelize then skips its own point check, one to four passes over the
  // points. The grid is the same either way. A box that does not hold every point puts the
  // points outside it in the data region's border voxels (never outside the grid).
  std::optional<Box3d> checked_bounds = std::nullopt;
};

struct Voxelization {
  // The grid: padding and data region, every voxel INSIDE except the data region's outer layer
  // (BOUNDARY: the paper's initial membrane on the exterior faces) and the padding (OUTSIDE,
  // generation 0). Voxels holding at least one point are HARD.
  VoxelGrid grid;
  Box3d bounds;                     // bounding box of the points, model units
  std::array<int, 3> data_dims{};   // voxels per axis covering the points (no padding)
  int64_t points = 0;
  int64_t hard_voxels = 0;
  int64_t voxels_with_one_point = 0;
  int64_t voxels_with_more_points = 0;
  // Voxels with >= 2 points / voxels with 1 point (section 4.3): a high value suggests a
  // smaller voxel. 0 when no voxel has exactly one point.
  double density_ratio = 0.0;
};

// The paper's formula (1): l = sqrt(2 (lx ly + ly lz + lz lx) / n_points), for the bounding
// box `bounds` of `points` points.
double EstimateVoxelSize(const Box3d& bounds, int64_t points);

// How many different points `points` holds (equal coordinates counted once): formula (1)'s
// n, since a point given twice samples the surface once (a file concatenated with itself, a
// scanner repeating its points). Linear expected time on `threads` threads: the points are
// grouped by a hash of their coordinates into buckets of a few thousand (equal points share a
// bucket; a copy of the points is held meanwhile), and each bucket's distinct points are
// counted in a hash set of its own. The passes ask `cancel` every 65536 points and stop once
// it has fired: the count is then meaningless, and the caller, who holds the token, knows it.
int64_t DistinctPointCount(absl::Span<const Point3f> points, int threads = 1,
                           const CancelToken& cancel = CancelToken::Never());

// Formula (1) for `points`, whose box is `bounds` (CheckedBounds'): EstimateVoxelSize over
// their distinct count (on `threads` threads). What Voxelize uses when no voxel size is given.
// Meaningless once `cancel` has fired (DistinctPointCount).
double FormulaVoxelSize(const Box3d& bounds, absl::Span<const Point3f> points, int threads = 1,
                        const CancelToken& cancel = CancelToken::Never());

// Bounding box of `points`. InvalidArgument when there are no points, when some coordinates
// are NaN or infinite (with their count), when all points are equal, or when they lie on one
// line or in one plane (up to float32 rounding): neither bounds a solid (a solid with a few
// points far from it is no plane). Four passes over the points, each asking `cancel` every
// 65536 points: Cancelled once it has fired.
absl::StatusOr<Box3d> CheckedBounds(absl::Span<const Point3f> points,
                                    const CancelToken& cancel = CancelToken::Never());

// Builds the voxel grid and the initial membrane for `points`, in the box
// options.checked_bounds when given, else in CheckedBounds'. Each axis gets
// n_d = floor(L_d / l) + 1 voxels (so the largest coordinate falls inside the grid) plus
// VoxelGrid::kPadding outside layers on every side. Point p lies in voxel
// floor((p - bounds.min) / l) + kPadding.
// Errors: InvalidArgument for degenerate points (see CheckedBounds; left to the caller when
// options.checked_bounds is given), a voxel size that is not finite and positive, or
// coordinates so far from the origin that float32 positions there are more than a quarter of a
// voxel apart (naming both), or so large that the grid around them passes float32's range
// (naming both ranges); ResourceExhausted, naming the grid and the budget, when the grid would
// exceed a positive options.voxel_budget (a negative one is InvalidArgument). Nothing is
// allocated before the budget check. `progress` counts the initial membrane's planes, then the
// points' voxels sorted and marked (counting never changes the grid). options.threads share
// the distinct count, the planes and the points' voxels (SortedPointVoxels), marked in slabs of
// z planes. Every task (a part of the distinct count's points, a plane, a block of 65536
// points, a slab) asks `cancel` first, and every worker stops once it has fired: Cancelled
// then, the grid freed (a cancel costs at most one task per thread after it; 10M points make
// tasks of a few milliseconds each).
// Writes z plane `z` of `grid` as the initial membrane (section 4.1): the kPadding layers
// OUTSIDE with generation label 0, the data region INSIDE soft, its outer layer BOUNDARY soft.
// Row by row (a grid of 2e9 voxels set one at a time took seconds); planes are independent,
// so callers may write them on several threads.
void WriteInitialPlane(int z, VoxelGrid& grid);

absl::StatusOr<Voxelization> Voxelize(absl::Span<const Point3f> points,
                                      const VoxelizeOptions& options,
                                      ProgressRange progress = ProgressRange(),
                                      const CancelToken& cancel = CancelToken::Never());

}  // namespace membrane

#endif  // MEMBRANE_CORE_ENGINE_VOXELIZATION_H_
