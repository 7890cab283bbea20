#include "core/engine/voxelization.h"

#include <algorithm>
#include <cmath>

#include "absl/container/flat_hash_set.h"
#include "absl/status/status.h"
#include "absl/strings/str_format.h"
#include "core/engine/point_density.h"

namespace membrane {

double EstimateVoxelSize(const Box3d& bounds, int64_t points) {
  const auto e = bounds.Extent();
  const double area2 = 2.0 * (e[0] * e[1] + e[1] * e[2] + e[2] * e[0]);
  return std::sqrt(area2 / static_cast<double>(std::max<int64_t>(points, 1)));
}

int64_t DistinctPointCount(absl::Span<const Point3f> points) {
  absl::flat_hash_set<Point3f> seen;
  seen.reserve(points.size());
  for (const Point3f& p : points) seen.insert(p);
  return static_cast<int64_t>(seen.size());
}

double FormulaVoxelSize(const Box3d& bounds, absl::Span<const Point3f> points) {
  return EstimateVoxelSize(bounds, DistinctPointCount(points));
}

absl::StatusOr<Box3d> CheckedBounds(absl::Span<const Point3f> points) {
  if (points.empty()) return absl::InvalidArgumentError("the point cloud has no points");
  int64_t non_finite = 0;
  Box3d box;
  bool first = true;
  for (const Point3f& p : points) {
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) {
      ++non_finite;
      continue;
    }
    for (int d = 0; d < 3; ++d) {
      if (first || p[d] < box.min[d]) box.min[d] = p[d];
      if (first || p[d] > box.max[d]) box.max[d] = p[d];
    }
    first = false;
  }
  if (non_finite > 0) {
    return absl::InvalidArgumentError(absl::StrFormat(
        "%d of %d points have NaN or infinite coordinates", non_finite, points.size()));
  }
  const auto e = box.Extent();
  if (e[0] == 0 && e[1] == 0 && e[2] == 0) {
    return absl::InvalidArgumentError(absl::StrFormat(
        "all %d points are equal (%g, %g, %g): a point bounds no solid", points.size(),
        box.min[0], box.min[1], box.min[2]));
  }
  // Coplanar (or collinear): the covariance matrix's smallest eigenvalue is zero next to its
  // largest. With l1 >= l2 >= l3, det / (sum of the principal 2x2 minors) is about l3 when l3
  // is small, and the trace about l1, so the test does not depend on the model's scale, nor
  // on how elongated it is. Comparing det with the cube of the mean eigenvalue would also call
  // a round blob with one stray point far away "coplanar".
  double mean[3] = {0, 0, 0};
  for (const Point3f& p : points)
    for (int d = 0; d < 3; ++d) mean[d] += p[d];
  for (double& m : mean) m /= static_cast<double>(points.size());
  double c[3][3] = {};
  for (const Point3f& p : points) {
    const double q[3] = {p[0] - mean[0], p[1] - mean[1], p[2] - mean[2]};
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) c[i][j] += q[i] * q[j];
  }
  const double det = c[0][0] * (c[1][1] * c[2][2] - c[1][2] * c[2][1]) -
                     c[0][1] * (c[1][0] * c[2][2] - c[1][2] * c[2][0]) +
                     c[0][2] * (c[1][0] * c[2][1] - c[1][1] * c[2][0]);
  const double minors = c[0][0] * c[1][1] - c[0][1] * c[1][0] + c[1][1] * c[2][2] -
                        c[1][2] * c[2][1] + c[0][0] * c[2][2] - c[0][2] * c[2][0];
  const double trace = c[0][0] + c[1][1] + c[2][2];
  if (det <= 1e-9 * minors * trace) {
    return absl::InvalidArgumentError(absl::StrFormat(
        "the %d points are coplanar (or collinear): a plane bounds no solid", points.size()));
  }
  return box;
}

namespace {

// Points are float32: far from the origin they sit on a lattice as coarse as the spacing of
// floats there (0.0625 at 1e6, 0.5 at 5e6: georeferenced scans). Coarser than a quarter of a
// voxel, the lattice leaves holes a membrane falls through, and the mesh comes back with a
// wrong genus without a word (a unit sphere at 1e6: genus 2); better to say so.
absl::Status CheckPositionPrecision(const Box3d& bounds, double voxel_size) {
  double reach = 0;
  for (int d = 0; d < 3; ++d)
    reach = std::max({reach, std::fabs(bounds.min[d]), std::fabs(bounds.max[d])});
  const auto far = static_cast<float>(reach);
  const double spacing = static_cast<double>(std::nextafter(far, HUGE_VALF)) - far;
  if (spacing <= voxel_size / 4) return absl::OkStatus();
  return absl::InvalidArgumentError(absl::StrFormat(
      "the coordinates reach %g, where float32 positions are %g apart: more than a quarter of "
      "the voxel size %g, so the points sit on a lattice too coarse for the surface; move the "
      "cloud near the origin (subtract its centre), or give its coordinates in double (text, or "
      "PLY or PCD doubles: membrane then moves it itself)",
      reach, spacing, voxel_size));
}

}  // namespace

absl::StatusOr<Voxelization> Voxelize(absl::Span<const Point3f> points,
                                      const VoxelizeOptions& options) {
  absl::StatusOr<Box3d> bounds = CheckedBounds(points);
  if (!bounds.ok()) return bounds.status();
  if (options.voxel_budget <= 0) {
    return absl::InvalidArgumentError(
        absl::StrFormat("voxel budget %d must be positive", options.voxel_budget));
  }
  double l = options.voxel_size;
  if (l == 0.0) l = FormulaVoxelSize(*bounds, points);
  if (!std::isfinite(l) || l <= 0.0) {
    return absl::InvalidArgumentError(
        absl::StrFormat("voxel size %g must be finite and positive", l));
  }
  if (absl::Status s = CheckPositionPrecision(*bounds, l); !s.ok()) return s;
  const auto extent = bounds->Extent();
  // Sizes in double first: a tiny voxel must give a clear status, not an integer overflow.
  double cells[3];
  double total = 1.0;
  for (int d = 0; d < 3; ++d) {
    cells[d] = std::floor(extent[d] / l) + 1.0 + 2.0 * VoxelGrid::kPadding;
    total *= cells[d];
  }
  if (total > static_cast<double>(options.voxel_budget) || cells[0] > 1e9 || cells[1] > 1e9 ||
      cells[2] > 1e9) {
    return absl::ResourceExhaustedError(absl::StrFormat(
        "voxel size %g gives a %.0fx%.0fx%.0f grid (%.3g voxels), over the voxel budget of %.3g",
        l, cells[0], cells[1], cells[2], total, static_cast<double>(options.voxel_budget)));
  }

  Voxelization v;
  v.bounds = *bounds;
  v.points = static_cast<int64_t>(points.size());
  std::array<int, 3> dims;
  for (int d = 0; d < 3; ++d) {
    dims[d] = static_cast<int>(cells[d]);
    v.data_dims[d] = dims[d] - 2 * VoxelGrid::kPadding;
  }
  const std::array<double, 3> origin = {bounds->min[0] - VoxelGrid::kPadding * l,
                                        bounds->min[1] - VoxelGrid::kPadding * l,
                                        bounds->min[2] - VoxelGrid::kPadding * l};
  v.grid = VoxelGrid(dims, origin, l, OutsideState(0));

  // Initial membrane: the data region is INSIDE, its outer layer BOUNDARY.
  const int p = VoxelGrid::kPadding;
  for (int z = p; z < dims[2] - p; ++z)
    for (int y = p; y < dims[1] - p; ++y)
      for (int x = p; x < dims[0] - p; ++x) {
        const bool outer = x == p || y == p || z == p || x == dims[0] - p - 1 ||
                           y == dims[1] - p - 1 || z == dims[2] - p - 1;
        v.grid.set(v.grid.Index(x, y, z), outer ? kBoundarySoft : kInsideSoft);
      }

  // Voxel of each point, sorted, so that runs give the points per voxel without a per-voxel
  // counter array.
  const std::vector<int64_t> sorted = SortedPointVoxels(points, *bounds, l, v.data_dims);
  const int64_t nx = v.data_dims[0], ny = v.data_dims[1];
  const PointDensity density = ForEachOccupiedVoxel(sorted, [&](int64_t voxel, int64_t) {
    const int64_t index = v.grid.Index(static_cast<int>(voxel % nx) + p,
                                       static_cast<int>(voxel / nx % ny) + p,
                                       static_cast<int>(voxel / (nx * ny)) + p);
    v.grid.set(index, IsBoundary(v.grid.at(index)) ? kBoundaryHard : kInsideHard);
  });
  v.voxels_with_one_point = density.voxels_with_one_point;
  v.voxels_with_more_points = density.voxels_with_more_points;
  v.hard_voxels = v.voxels_with_one_point + v.voxels_with_more_points;
  v.density_ratio = density.ratio();
  return v;
}

}  // namespace membrane
