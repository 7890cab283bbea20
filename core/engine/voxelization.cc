#include "core/engine/voxelization.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <limits>
#include <numeric>
#include <string>
#include <utility>

#include "absl/container/flat_hash_set.h"
#include "absl/hash/hash.h"
#include "absl/status/status.h"
#include "absl/strings/str_format.h"
#include "core/base/bucket_offsets.h"
#include "core/base/parallel_tasks.h"
#include "core/engine/point_density.h"
#include "core/geometry/vec3.h"

namespace membrane {
namespace {

// Points between two asks of the cancel token in the passes over the points: a few ms of work.
constexpr size_t kPollPoints = size_t{1} << 16;

// Calls visit(point) for each of `points` in order, asking `cancel` every kPollPoints points.
// False when it fired (the visits then stop short).
template <typename Visit>
bool VisitPoints(absl::Span<const Point3f> points, const CancelToken& cancel, Visit visit) {
  for (size_t start = 0; start < points.size(); start += kPollPoints) {
    if (cancel.cancelled()) return false;
    const size_t end = std::min(points.size(), start + kPollPoints);
    for (size_t i = start; i < end; ++i) visit(i, points[i]);
  }
  return true;
}

absl::Status CheckCancelled() { return absl::CancelledError("point check cancelled"); }

}  // namespace

double EstimateVoxelSize(const Box3d& bounds, int64_t points) {
  const auto e = bounds.Extent();
  const double area2 = 2.0 * (e[0] * e[1] + e[1] * e[2] + e[2] * e[0]);
  return std::sqrt(area2 / static_cast<double>(std::max<int64_t>(points, 1)));
}

int64_t DistinctPointCount(absl::Span<const Point3f> points, int threads,
                           const CancelToken& cancel) {
  // Equal points share a bucket of their hash's top bits, and each bucket, a few thousand
  // points, is counted in a hash set of its own that stays in the cache: one set of every
  // point missed the cache at nearly each insert (10M points: 2-6 s on 2 threads). absl's hash
  // is seeded per process, so no upload can pile its points into one bucket on purpose; it
  // hashes +0 and -0 alike, as the sets' equality needs.
  constexpr size_t kBucketPoints = 4096;
  constexpr int kMaxBucketBits = 20;
  const size_t n = points.size();
  int bits = 0;
  while (bits < kMaxBucketBits && (n >> bits) > kBucketPoints) ++bits;
  const size_t buckets = size_t{1} << bits;
  const auto bucket_of = [bits](const Point3f& p) -> size_t {
    return bits == 0 ? 0 : static_cast<size_t>(absl::HashOf(p) >> (64 - bits));
  };
  // The points in blocks, one task each, counted and then moved into their buckets' order.
  const int64_t blocks = std::clamp<int64_t>(threads, 1, static_cast<int64_t>(n / kPollPoints) + 1);
  const auto block_points = [&](int64_t block) {
    const size_t begin = n * static_cast<size_t>(block) / static_cast<size_t>(blocks);
    const size_t end = n * static_cast<size_t>(block + 1) / static_cast<size_t>(blocks);
    return points.subspan(begin, end - begin);
  };
  std::vector<std::vector<size_t>> offsets(blocks, std::vector<size_t>(buckets, 0));
  RunTasks(threads, blocks, [&](int, int64_t block) {
    std::vector<size_t>& count = offsets[block];
    VisitPoints(block_points(block), cancel,
                [&](size_t, const Point3f& p) { ++count[bucket_of(p)]; });
  });
  if (cancel.cancelled()) return 0;
  const std::vector<size_t> bucket_start = PlaceBucketsByPart(offsets);
  // Sized unset: every point is written below, on the threads, which take its pages' faults.
  std::vector<Point3f, UnsetAllocator<Point3f>> grouped(n);
  RunTasks(threads, blocks, [&](int, int64_t block) {
    std::vector<size_t>& at = offsets[block];
    VisitPoints(block_points(block), cancel,
                [&](size_t, const Point3f& p) { grouped[at[bucket_of(p)]++] = p; });
  });
  if (cancel.cancelled()) return 0;
  offsets.clear();
  // Buckets in runs of about kPollPoints points a task, each run's count its own.
  const int64_t runs = static_cast<int64_t>(n / kPollPoints) + 1;
  std::vector<int64_t> distinct(runs, 0);
  RunTasks(threads, runs, [&](int, int64_t run) {
    if (cancel.cancelled()) return;
    const size_t first = buckets * static_cast<size_t>(run) / static_cast<size_t>(runs);
    const size_t last = buckets * static_cast<size_t>(run + 1) / static_cast<size_t>(runs);
    absl::flat_hash_set<Point3f> seen;
    for (size_t b = first; b < last; ++b) {
      seen.clear();
      seen.reserve(bucket_start[b + 1] - bucket_start[b]);
      for (size_t i = bucket_start[b]; i < bucket_start[b + 1]; ++i) seen.insert(grouped[i]);
      distinct[run] += static_cast<int64_t>(seen.size());
    }
  });
  return std::accumulate(distinct.begin(), distinct.end(), int64_t{0});
}

double FormulaVoxelSize(const Box3d& bounds, absl::Span<const Point3f> points, int threads,
                        const CancelToken& cancel) {
  return EstimateVoxelSize(bounds, DistinctPointCount(points, threads, cancel));
}

namespace {

// a - b, in double.
Vec3d Sub(const Point3f& a, const Point3f& b) { return ToVec3d(a) - ToVec3d(b); }

// The spacing of float32 values at the magnitude of `p`'s largest coordinate (finite): the
// next float up is the one whose bits are one more, which is what nextafter computes, at a
// fraction of a library call's cost (this runs for every point, twice).
double FloatStep(const Point3f& p) {
  const float m = std::max({std::fabs(p[0]), std::fabs(p[1]), std::fabs(p[2])});
  const float next = std::bit_cast<float>(std::bit_cast<uint32_t>(m) + 1u);
  return static_cast<double>(next) - m;
}


// InvalidArgument when `points` (not all equal, finite) lie on one line or in one plane,
// which bound no solid. Geometric, in the manner of quickhull's first simplex: a, then b the
// point farthest from a, c the farthest from the line ab; the points are collinear when all
// are on ab, coplanar when all are on the plane abc. "On" allows for float32 rounding: 2 steps
// at the point's own magnitude and at a's and c's, and at b's scaled by how far along ab the
// point is (a point exactly on a plane, rounded, is within 0.87 of a step of it, and so are
// the three that give the plane). Too little allowance only lets a plane through to the
// voxelizer, which then finds no solid in it; too much would call a small solid far from
// the origin flat. No spread statistic can say this: a round blob
// with one point far away has a covariance as thin as a plane's, and is no plane.
absl::Status CheckSpansASolid(absl::Span<const Point3f> points, const CancelToken& cancel) {
  const Point3f& a = points.front();
  size_t b_index = 0;
  double b_distance = -1;
  if (!VisitPoints(points, cancel, [&](size_t i, const Point3f& p) {
        const Vec3d ap = Sub(p, a);
        if (const double d = Dot(ap, ap); d > b_distance) b_distance = d, b_index = i;
      })) {
    return CheckCancelled();
  }
  const Point3f& b = points[b_index];
  const Vec3d ab = Sub(b, a);
  const double ab_length = std::sqrt(b_distance);
  const double a_step = FloatStep(a), b_step = FloatStep(b);
  // The rounding allowance at `p` of a line or plane through a, b and a third point whose
  // float step is `third_step`.
  auto allowance = [&](const Point3f& p, double third_step) {
    const Vec3d ap = Sub(p, a);
    return 2 * (FloatStep(p) + a_step + third_step + b_step * std::sqrt(Dot(ap, ap)) / ab_length);
  };
  size_t c_index = 0;
  double c_distance = -1, line_excess = -1;
  if (!VisitPoints(points, cancel, [&](size_t i, const Point3f& p) {
        const Vec3d n = Cross(Sub(p, a), ab);
        const double d = std::sqrt(Dot(n, n)) / ab_length;
        if (d > c_distance) c_distance = d, c_index = i;
        line_excess = std::max(line_excess, d - allowance(p, 0));
      })) {
    return CheckCancelled();
  }
  if (line_excess <= 0) {
    return absl::InvalidArgumentError(absl::StrFormat(
        "the %d points are collinear (none farther than %g from one line): a line bounds no "
        "solid",
        points.size(), c_distance));
  }
  const Point3f& c = points[c_index];
  Vec3d normal = Cross(ab, Sub(c, a));
  const double normal_length = std::sqrt(Dot(normal, normal));
  for (double& v : normal) v /= normal_length;
  const double c_step = FloatStep(c);
  double d_distance = 0, plane_excess = -1;
  if (!VisitPoints(points, cancel, [&](size_t, const Point3f& p) {
        const double d = std::fabs(Dot(Sub(p, a), normal));
        d_distance = std::max(d_distance, d);
        plane_excess = std::max(plane_excess, d - allowance(p, c_step));
      })) {
    return CheckCancelled();
  }
  if (plane_excess <= 0) {
    return absl::InvalidArgumentError(absl::StrFormat(
        "the %d points are coplanar (none farther than %g from one plane): a plane bounds no "
        "solid",
        points.size(), d_distance));
  }
  return absl::OkStatus();
}

}  // namespace

absl::StatusOr<Box3d> CheckedBounds(absl::Span<const Point3f> points,
                                    const CancelToken& cancel) {
  if (points.empty()) return absl::InvalidArgumentError("the point cloud has no points");
  int64_t non_finite = 0;
  Box3d box;
  bool first = true;
  if (!VisitPoints(points, cancel, [&](size_t, const Point3f& p) {
        if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) {
          ++non_finite;
          return;
        }
        for (int d = 0; d < 3; ++d) {
          if (first || p[d] < box.min[d]) box.min[d] = p[d];
          if (first || p[d] > box.max[d]) box.max[d] = p[d];
        }
        first = false;
      })) {
    return CheckCancelled();
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
  // Where float32 positions are coarse against the cloud's size (a small object at survey
  // coordinates), the rounding allowance of CheckSpansASolid is as wide as the object and
  // would call it a line; CheckPositionPrecision then names the real problem, the lattice.
  const double widest = std::max({e[0], e[1], e[2]});
  Point3f far_corner;
  for (int d = 0; d < 3; ++d) {
    far_corner[d] = static_cast<float>(std::max(std::fabs(box.min[d]), std::fabs(box.max[d])));
  }
  if (16 * FloatStep(far_corner) < widest) {
    if (absl::Status s = CheckSpansASolid(points, cancel); !s.ok()) return s;
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

// Mesh positions are float32, on a cube of the grid's largest side from its origin (the
// output grid, core/mesh/output_grid.h): coordinates near float32's largest value (3.4e38)
// would put that cube's far side, or its length, at infinity. InvalidArgument naming the
// cloud's range and the grid's when they do not fit in 0.99 of it.
absl::Status CheckGridFitsFloat(const Box3d& bounds, double voxel_size, const double cells[3]) {
  constexpr double kLimit = 0.99 * std::numeric_limits<float>::max();
  const double side = voxel_size * std::max({cells[0], cells[1], cells[2]});
  double low = std::numeric_limits<double>::infinity(), high = -low;
  for (int d = 0; d < 3; ++d) {
    const double origin = bounds.min[d] - VoxelGrid::kPadding * voxel_size;
    low = std::min(low, origin);
    high = std::max(high, origin + side);
  }
  if (std::max({side, std::fabs(low), std::fabs(high)}) <= kLimit) return absl::OkStatus();
  double cloud_low = bounds.min[0], cloud_high = bounds.max[0];
  for (int d = 1; d < 3; ++d) {
    cloud_low = std::min(cloud_low, bounds.min[d]);
    cloud_high = std::max(cloud_high, bounds.max[d]);
  }
  return absl::InvalidArgumentError(absl::StrFormat(
      "the coordinates span [%.3g, %.3g]: at voxel size %.3g the grid around them spans "
      "[%.3g, %.3g] (a cube of side %.3g), past the +-%.3g that float32 mesh positions can hold; scale the "
      "cloud down or move it toward the origin",
      cloud_low, cloud_high, voxel_size, low, high, side, kLimit));
}

// Makes HARD the voxel of every entry of `sorted` (SortedPointVoxels over `data_dims`) and
// counts the occupied voxels. Tasks take slabs of z planes (8, or more for a grid of over 32k
// planes, so that there are at most 4096), found by the first entry of each: a voxel's run
// never spans two, and no two tasks write the same plane.
PointDensity MarkHardVoxels(absl::Span<const int64_t> sorted, const std::array<int, 3>& data_dims,
                            int threads, const CancelToken& cancel, VoxelGrid& grid) {
  constexpr int64_t kMaxSlabs = 4096;
  const int p = VoxelGrid::kPadding;
  const int64_t nx = data_dims[0], ny = data_dims[1], nz = data_dims[2];
  const int64_t slab_planes = std::max<int64_t>(8, (nz + kMaxSlabs - 1) / kMaxSlabs);
  const int64_t slabs = (nz + slab_planes - 1) / slab_planes;
  auto first_of_slab = [&](int64_t s) {
    return std::lower_bound(sorted.begin(), sorted.end(), s * slab_planes * nx * ny) -
           sorted.begin();
  };
  std::vector<PointDensity> parts(slabs);
  TaskCancel stop(cancel, threads, 1);
  RunTasks(threads, slabs, [&](int worker, int64_t s) {
    if (stop.Poll(worker)) return;
    const int64_t begin = first_of_slab(s);
    parts[s] = ForEachOccupiedVoxel(
        sorted.subspan(begin, first_of_slab(s + 1) - begin), [&](int64_t voxel, int64_t) {
          const int64_t index = grid.Index(static_cast<int>(voxel % nx) + p,
                                           static_cast<int>(voxel / nx % ny) + p,
                                           static_cast<int>(voxel / (nx * ny)) + p);
          grid.set(index, IsBoundary(grid.at(index)) ? kBoundaryHard : kInsideHard);
        });
  });
  PointDensity total;
  for (const PointDensity& d : parts) {
    total.voxels_with_one_point += d.voxels_with_one_point;
    total.voxels_with_more_points += d.voxels_with_more_points;
  }
  return total;
}

}  // namespace

void WriteInitialPlane(int z, VoxelGrid& grid) {
  const int p = VoxelGrid::kPadding;
  const std::array<int, 3>& dims = grid.dims();
  const int64_t row_length = dims[0] - 2 * p;
  VoxelState* states = grid.mutable_states().data();
  VoxelState* plane = states + grid.Index(0, 0, z);
  const int64_t plane_size = static_cast<int64_t>(dims[0]) * dims[1];
  if (z < p || z >= dims[2] - p) {
    std::fill(plane, plane + plane_size, OutsideState(0));
    return;
  }
  std::fill(plane, plane + static_cast<int64_t>(dims[0]) * p, OutsideState(0));
  for (int y = p; y < dims[1] - p; ++y) {
    VoxelState* row = states + grid.Index(p, y, z);
    const bool outer = y == p || z == p || y == dims[1] - p - 1 || z == dims[2] - p - 1;
    std::fill(row - p, row, OutsideState(0));
    std::fill(row, row + row_length, outer ? kBoundarySoft : kInsideSoft);
    row[0] = kBoundarySoft;
    row[row_length - 1] = kBoundarySoft;
    std::fill(row + row_length, row + row_length + p, OutsideState(0));
  }
  std::fill(plane + static_cast<int64_t>(dims[0]) * (dims[1] - p), plane + plane_size,
            OutsideState(0));
}

absl::StatusOr<Voxelization> Voxelize(absl::Span<const Point3f> points,
                                      const VoxelizeOptions& options, ProgressRange progress,
                                      const CancelToken& cancel) {
  const auto cancelled = [] { return absl::CancelledError("voxelization cancelled"); };
  absl::StatusOr<Box3d> bounds = options.checked_bounds
                                      ? absl::StatusOr<Box3d>(*options.checked_bounds)
                                      : CheckedBounds(points, cancel);
  if (cancel.cancelled()) return cancelled();
  if (!bounds.ok()) return bounds.status();
  if (options.voxel_budget < 0) {
    return absl::InvalidArgumentError(absl::StrFormat(
        "voxel budget %d must be positive, or 0 for none", options.voxel_budget));
  }
  double l = options.voxel_size;
  if (l == 0.0) l = FormulaVoxelSize(*bounds, points, options.threads, cancel);
  // Before the grid is allocated: a cancelled run takes no memory.
  if (cancel.cancelled()) return cancelled();
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
  const bool over_budget =
      options.voxel_budget > 0 && total > static_cast<double>(options.voxel_budget);
  if (over_budget || cells[0] > 1e9 || cells[1] > 1e9 || cells[2] > 1e9) {
    const std::string limit =
        over_budget ? absl::StrFormat("the voxel budget of %.3g",
                                      static_cast<double>(options.voxel_budget))
                    : std::string("the largest grid side of 1e9 voxels");
    return absl::ResourceExhaustedError(
        absl::StrFormat("voxel size %g gives a %.0fx%.0fx%.0f grid (%.3g voxels), over %s", l,
                        cells[0], cells[1], cells[2], total, limit));
  }

  if (absl::Status s = CheckGridFitsFloat(*bounds, l, cells); !s.ok()) return s;

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
  v.grid = VoxelGrid(dims, origin, l, VoxelGrid::Unset{});

  // Every voxel is written here once (WriteInitialPlane), a z plane a task, on the run's
  // threads: the grid's first writes are its page faults.
  // Half for the planes, half for the points: the planes follow the grid's volume and the sort
  // the points' count, and either can be the larger.
  const ProgressRange planes = progress.Part(0, 0.5);
  planes.Begin(dims[2]);
  TaskCancel stop(cancel, options.threads, 1);
  RunTasks(options.threads, dims[2], [&](int worker, int64_t task) {
    if (stop.Poll(worker)) return;
    WriteInitialPlane(static_cast<int>(task), v.grid);
    planes.Add(1);
  });
  if (stop.fired()) return cancelled();

  // Voxel of each point, sorted, so that runs give the points per voxel without a per-voxel
  // counter array.
  const std::vector<int64_t> sorted =
      SortedPointVoxels(points, *bounds, l, v.data_dims, options.threads, cancel);
  if (cancel.cancelled()) return cancelled();
  progress.Part(0.5, 0.9).Done();
  const PointDensity density =
      MarkHardVoxels(sorted, v.data_dims, options.threads, cancel, v.grid);
  if (cancel.cancelled()) return cancelled();
  v.voxels_with_one_point = density.voxels_with_one_point;
  v.voxels_with_more_points = density.voxels_with_more_points;
  v.hard_voxels = v.voxels_with_one_point + v.voxels_with_more_points;
  v.density_ratio = density.ratio();
  progress.Part(0.9, 1).Done();
  return v;
}

}  // namespace membrane
