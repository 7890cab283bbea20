#include "core/engine/hard_voxel_points.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <utility>

#include "core/base/parallel_tasks.h"
#include "core/base/split_sort.h"
#include "core/engine/point_density.h"
#include "core/geometry/symmetric_eigen3.h"

namespace membrane {
namespace {

// A point's voxel beside its index, ordered as the pair (voxel, point). A trivial type, so that
// the sort's arrays are left unset when made: std::pair's constructor zeroes its members, a
// serial pass over 10M pairs (160 MB of fresh pages) and again over the merge's buffer.
struct VoxelPoint {
  int64_t voxel;
  uint32_t point;
  friend bool operator<(const VoxelPoint& a, const VoxelPoint& b) {
    return a.voxel != b.voxel ? a.voxel < b.voxel : a.point < b.point;
  }
};

// The voxels within Chebyshev distance `radius` of `c`, clipped to the grid: [a, b].
void CubeAround(const VoxelGrid& grid, const Coord& c, int radius, Coord& a, Coord& b) {
  for (int d = 0; d < 3; ++d) {
    a[d] = std::max(c[d] - radius, 0);
    b[d] = std::min(c[d] + radius, grid.dim(d) - 1);
  }
}

}  // namespace

HardVoxelPoints::HardVoxelPoints(const VoxelGrid& grid, absl::Span<const Point3f> points,
                                 int threads) {
  const auto& origin = grid.origin();
  const double l = grid.voxel_size();
  const double inv = 1.0 / l;
  // Voxelize put a point in voxel DataVoxelAlong(p, min, l) past the padding, min the points'
  // least coordinate. Computed from the origin (min - padding * l) instead, the rounding differs
  // on voxel faces, and the box's least face is one: the points of a flat base there would be
  // read in the padding, off their hard voxel. Their minimum gives Voxelize's voxel exactly
  // when the grid was voxelized from them; another grid is read from its origin.
  std::array<double, 3> low = origin;
  int pad = 0;
  if (!points.empty()) {
    Point3f least = points[0];
    for (const Point3f& p : points)
      for (int d = 0; d < 3; ++d) least[d] = std::min(least[d], p[d]);
    bool voxelized = true;
    for (int d = 0; d < 3; ++d) {
      voxelized = voxelized && least[d] - VoxelGrid::kPadding * l == origin[d];
    }
    if (voxelized) {
      low = {least[0], least[1], least[2]};
      pad = VoxelGrid::kPadding;
    }
  }
  // (voxel, point) pairs are unique: the same order on any thread count.
  Array<VoxelPoint> order(points.size());
  MakeAndSortUnique(order, threads, [&](size_t i) {
    Coord c;
    for (int d = 0; d < 3; ++d) {
      const int64_t along = DataVoxelAlong(points[i][d], low[d], l, grid.dim(d) - 2 * pad);
      c[d] = pad + static_cast<int>(along);
    }
    return VoxelPoint{grid.Index(c), static_cast<uint32_t>(i)};
  });
  // The index is filled on the run's threads, in spans of `order`: each span counts the voxels
  // it starts, then writes them at the count of the spans before it. The points are read at
  // random (a 10M-point cloud's order is its file's), which one thread pays in cache misses.
  const size_t n = order.size();
  const int64_t spans = threads > 1 && n >= kMinSplitItems ? 8 * int64_t{threads} : 1;
  auto span_begin = [&](int64_t t) { return n * static_cast<size_t>(t) / static_cast<size_t>(spans); };
  auto starts_voxel = [&](size_t k) { return k == 0 || order[k].voxel != order[k - 1].voxel; };
  std::vector<size_t> first_voxel(static_cast<size_t>(spans) + 1, 0);
  RunTasks(threads, spans, [&](int, int64_t t) {
    size_t count = 0;
    for (size_t k = span_begin(t); k < span_begin(t + 1); ++k) count += starts_voxel(k);
    first_voxel[static_cast<size_t>(t) + 1] = count;
  });
  for (size_t t = 1; t < first_voxel.size(); ++t) first_voxel[t] += first_voxel[t - 1];
  voxels_.resize(first_voxel.back());
  starts_.resize(first_voxel.back() + 1);
  positions_.resize(n);
  RunTasks(threads, spans, [&](int, int64_t t) {
    size_t v = first_voxel[static_cast<size_t>(t)];
    for (size_t k = span_begin(t); k < span_begin(t + 1); ++k) {
      if (starts_voxel(k)) {
        voxels_[v] = order[k].voxel;
        starts_[v] = static_cast<uint32_t>(k);
        ++v;
      }
      const Point3f& p = points[order[k].point];
      positions_[k] = {static_cast<float>((p[0] - origin[0]) * inv),
                       static_cast<float>((p[1] - origin[1]) * inv),
                       static_cast<float>((p[2] - origin[2]) * inv)};
    }
  });
  starts_.back() = static_cast<uint32_t>(n);
}

template <typename F>
void HardVoxelPoints::ForEachPoint(const VoxelGrid& grid, const Coord& a, const Coord& b,
                                   F f) const {
  for (int z = a.z; z <= b.z; ++z)
    for (int y = a.y; y <= b.y; ++y) {
      // The box's voxels of one x-row are consecutive indices.
      const int64_t first = grid.Index(a.x, y, z), last = grid.Index(b.x, y, z);
      for (size_t k = std::lower_bound(voxels_.begin(), voxels_.end(), first) - voxels_.begin();
           k < voxels_.size() && voxels_[k] <= last; ++k) {
        for (uint32_t i = starts_[k]; i < starts_[k + 1]; ++i) f(positions_[i]);
      }
    }
}

bool HardVoxelPoints::BoxMoments(const VoxelGrid& grid, const Coord& lo, const Coord& hi,
                                 Moments& m) const {
  Coord a, b;
  for (int d = 0; d < 3; ++d) {
    a[d] = std::max(lo[d], 0);
    b[d] = std::min(hi[d], grid.dim(d) - 1);
    if (a[d] > b[d]) return false;
  }
  // Sums relative to the box's centre, so that they stay small.
  const double cx = 0.5 * (a.x + b.x + 1), cy = 0.5 * (a.y + b.y + 1), cz = 0.5 * (a.z + b.z + 1);
  double n = 0, sx = 0, sy = 0, sz = 0, sxx = 0, sxy = 0, sxz = 0, syy = 0, syz = 0, szz = 0;
  ForEachPoint(grid, a, b, [&](const std::array<float, 3>& p) {
    const double x = p[0] - cx, y = p[1] - cy, z = p[2] - cz;
    n += 1;
    sx += x, sy += y, sz += z;
    sxx += x * x, sxy += x * y, sxz += x * z;
    syy += y * y, syz += y * z, szz += z * z;
  });
  m.n = n;
  if (n == 0) return true;
  const double mx = sx / n, my = sy / n, mz = sz / n;
  m.cov = {sxx / n - mx * mx, sxy / n - mx * my, sxz / n - mx * mz,
           syy / n - my * my, syz / n - my * mz, szz / n - mz * mz};
  return true;
}

double HardVoxelPoints::PlaneSpread(const VoxelGrid& grid, const Coord& lo, const Coord& hi,
                                    int min_points) const {
  Moments m;
  if (!BoxMoments(grid, lo, hi, m) || m.n < min_points) return -1;
  return std::sqrt(std::max(0.0, SymmetricEigenvalues(m.cov).smallest));
}

bool HardVoxelPoints::PlaneNormal(const VoxelGrid& grid, const Coord& lo, const Coord& hi,
                                  std::array<double, 3>& normal, int min_points) const {
  Moments m;
  if (!BoxMoments(grid, lo, hi, m) || m.n < min_points) return false;
  const std::optional<Vec3d> found = EigenvectorOf(m.cov, SymmetricEigenvalues(m.cov).smallest);
  if (!found) return false;
  normal = *found;
  return true;
}

double HardVoxelPoints::NearestDistance(const VoxelGrid& grid, const Coord& c, int radius) const {
  Coord a, b;
  CubeAround(grid, c, radius, a, b);
  double best2 = static_cast<double>(radius + 1) * (radius + 1);
  ForEachPoint(grid, a, b, [&](const std::array<float, 3>& p) {
    const double x = p[0] - (c.x + 0.5), y = p[1] - (c.y + 0.5), z = p[2] - (c.z + 0.5);
    best2 = std::min(best2, x * x + y * y + z * z);
  });
  return std::sqrt(best2);
}

bool HardVoxelPoints::FacingPatch(const VoxelGrid& grid, const Coord& c, int radius,
                                  double band, int min_count, double max_band,
                                  Patch& patch) const {
  Coord a, b;
  CubeAround(grid, c, radius, a, b);
  const double cx = c.x + 0.5, cy = c.y + 0.5, cz = c.z + 0.5;
  auto distance2 = [&](const std::array<float, 3>& p) {
    const double x = p[0] - cx, y = p[1] - cy, z = p[2] - cz;
    return x * x + y * y + z * z;
  };
  // Two passes over a few voxels' points: the min_count nearest first (ascending, -1 where
  // fewer were read), then the band beyond the nearest.
  constexpr int kMaxCount = 8;
  const int k = std::clamp(min_count, 1, kMaxCount);
  std::array<double, kMaxCount> nearest2;
  nearest2.fill(-1);
  ForEachPoint(grid, a, b, [&](const std::array<float, 3>& p) {
    double d2 = distance2(p);
    for (int j = 0; j < k; ++j) {
      if (nearest2[j] < 0) {
        nearest2[j] = d2;
        return;
      }
      if (d2 < nearest2[j]) std::swap(d2, nearest2[j]);
    }
  });
  if (nearest2[0] < 0) return false;
  const double nearest = std::sqrt(nearest2[0]);
  // The band, or as far as the min_count-th nearest point (all read when fewer) within
  // max_band.
  double farthest2 = nearest2[0];
  for (int j = 0; j < k && nearest2[j] >= 0; ++j) farthest2 = nearest2[j];
  const double reach =
      nearest + std::clamp(std::sqrt(farthest2) - nearest, band, std::max(band, max_band));
  const double reach2 = reach * reach;
  // Sums relative to the voxel's centre, so that they stay small.
  double n = 0;
  std::array<double, 3> s{};
  std::array<double, 6> ss{};
  ForEachPoint(grid, a, b, [&](const std::array<float, 3>& p) {
    if (distance2(p) > reach2) return;
    const double x = p[0] - cx, y = p[1] - cy, z = p[2] - cz;
    n += 1;
    s[0] += x, s[1] += y, s[2] += z;
    ss[0] += x * x, ss[1] += x * y, ss[2] += x * z, ss[3] += y * y, ss[4] += y * z, ss[5] += z * z;
  });
  const double mx = s[0] / n, my = s[1] / n, mz = s[2] / n;
  patch.count = n;
  patch.mean = {cx + mx, cy + my, cz + mz};
  patch.scatter = {ss[0] - n * mx * mx, ss[1] - n * mx * my, ss[2] - n * mx * mz,
                   ss[3] - n * my * my, ss[4] - n * my * mz, ss[5] - n * mz * mz};
  return true;
}

void HardVoxelPoints::SpotDistances(const VoxelGrid& grid, const Coord& c, int radius,
                                    int samples, std::vector<double>& distances) const {
  Coord a, b;
  CubeAround(grid, c, radius, a, b);
  const double cap2 = static_cast<double>(radius + 1) * (radius + 1);
  distances.assign(static_cast<size_t>(samples) * samples * samples, cap2);
  ForEachPoint(grid, a, b, [&](const std::array<float, 3>& p) {
    size_t n = 0;
    for (int k = 0; k < samples; ++k)
      for (int j = 0; j < samples; ++j)
        for (int i = 0; i < samples; ++i, ++n) {
          const double x = p[0] - (c.x + (i + 0.5) / samples),
                       y = p[1] - (c.y + (j + 0.5) / samples),
                       z = p[2] - (c.z + (k + 0.5) / samples);
          distances[n] = std::min(distances[n], x * x + y * y + z * z);
        }
  });
  for (double& d : distances) d = std::sqrt(d);
}

bool HardVoxelPoints::PointsWithin(size_t ia, size_t ib, double reach) const {
  const double reach2 = reach * reach;
  for (uint32_t i = starts_[ia]; i < starts_[ia + 1]; ++i)
    for (uint32_t j = starts_[ib]; j < starts_[ib + 1]; ++j) {
      double d2 = 0;
      for (int d = 0; d < 3; ++d) {
        const double e = static_cast<double>(positions_[i][d]) - positions_[j][d];
        d2 += e * e;
      }
      if (d2 <= reach2) return true;
    }
  return false;
}

}  // namespace membrane
