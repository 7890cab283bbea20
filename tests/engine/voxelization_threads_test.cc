// Voxelize, DistinctPointCount and SortedPointVoxels on several threads give what one thread
// gives: the work is split by blocks of points and slabs of z planes, never by the count.
#include <algorithm>
#include <cmath>
#include <vector>

#include "core/engine/point_density.h"
#include "core/engine/voxelization.h"
#include "gtest/gtest.h"

namespace membrane {
namespace {

// A sphere of `n` points, denser near its poles (voxels with one and with several points),
// with its first tenth given again, so that blocks of points, slabs of planes and duplicates
// all come into play.
std::vector<Point3f> UnevenSphere(int n) {
  std::vector<Point3f> points;
  for (int i = 0; i < n; ++i) {
    const double u = (i + 0.5) / n;
    const double z = std::copysign(std::pow(std::fabs(2 * u - 1), 0.7), 2 * u - 1);
    const double r = std::sqrt(std::max(0.0, 1 - z * z)), t = 2.399963 * i;
    points.push_back({float(r * std::cos(t)), float(r * std::sin(t)), float(z)});
  }
  points.insert(points.end(), points.begin(), points.begin() + n / 10);
  return points;
}

TEST(VoxelizationThreads, GridAndCountsAreTheSameForAnyThreadCount) {
  const std::vector<Point3f> points = UnevenSphere(200000);
  absl::StatusOr<Voxelization> one = Voxelize(points, {});
  ASSERT_TRUE(one.ok()) << one.status();
  ASSERT_GT(one->voxels_with_one_point, 0);
  ASSERT_GT(one->voxels_with_more_points, 0);
  for (int threads : {2, 3, 4, 7}) {
    absl::StatusOr<Voxelization> v = Voxelize(points, VoxelizeOptions{.threads = threads});
    ASSERT_TRUE(v.ok()) << v.status();
    EXPECT_EQ(v->grid.voxel_size(), one->grid.voxel_size()) << threads;
    EXPECT_EQ(v->grid.dims(), one->grid.dims()) << threads;
    EXPECT_TRUE(v->grid.states() == one->grid.states()) << threads << " threads";
    EXPECT_EQ(v->hard_voxels, one->hard_voxels) << threads;
    EXPECT_EQ(v->voxels_with_one_point, one->voxels_with_one_point) << threads;
    EXPECT_EQ(v->voxels_with_more_points, one->voxels_with_more_points) << threads;
  }
}

TEST(VoxelizationThreads, EveryVoxelHoldsTheInitialMembraneOnAnyThreadCount) {
  // The grid is allocated unset and written plane by plane: the padding OUTSIDE (generation
  // 0), the data region's outer layer BOUNDARY and its inside INSIDE, hard where points are.
  // Odd sizes, so that the padding rows and columns differ in length.
  std::vector<Point3f> points = UnevenSphere(3000);
  for (Point3f& p : points) p[0] *= 1.7f;
  for (int threads : {1, 2, 3}) {
    absl::StatusOr<Voxelization> v =
        Voxelize(points, VoxelizeOptions{.voxel_size = 0.09, .threads = threads});
    ASSERT_TRUE(v.ok()) << v.status();
    const VoxelGrid& g = v->grid;
    const int p = VoxelGrid::kPadding;
    ASSERT_NE(g.dim(0), g.dim(1));
    int64_t hard = 0;
    for (int z = 0; z < g.dim(2); ++z)
      for (int y = 0; y < g.dim(1); ++y)
        for (int x = 0; x < g.dim(0); ++x) {
          const Coord c{x, y, z};
          const VoxelState s = g.at(c);
          bool padding = false, outer = false;
          for (int d = 0; d < 3; ++d) {
            padding = padding || c[d] < p || c[d] >= g.dim(d) - p;
            outer = outer || c[d] == p || c[d] == g.dim(d) - p - 1;
          }
          hard += IsHard(s);
          if (padding) {
            ASSERT_EQ(s, OutsideState(0)) << x << " " << y << " " << z << ", " << threads;
          } else if (outer) {
            ASSERT_TRUE(IsBoundary(s)) << x << " " << y << " " << z << ", " << threads;
          } else {
            ASSERT_TRUE(IsInside(s)) << x << " " << y << " " << z << ", " << threads;
          }
        }
    EXPECT_EQ(hard, v->hard_voxels) << threads;
  }
}

TEST(VoxelizationThreads, TallGridOfManySlabsIsTheSameForAnyThreadCount) {
  // 40,000 planes: slabs of more than 8 planes each.
  std::vector<Point3f> points;
  for (int i = 0; i < 120000; ++i) {
    const double t = 0.61 * i;
    points.push_back({float(std::cos(t)), float(std::sin(t)), float(i / 3.0)});
  }
  const VoxelizeOptions one_thread{.voxel_size = 1.0};
  absl::StatusOr<Voxelization> one = Voxelize(points, one_thread);
  ASSERT_TRUE(one.ok()) << one.status();
  ASSERT_GT(one->grid.dim(2), 40000);
  absl::StatusOr<Voxelization> three = Voxelize(points, {.voxel_size = 1.0, .threads = 3});
  ASSERT_TRUE(three.ok()) << three.status();
  EXPECT_TRUE(three->grid.states() == one->grid.states());
  EXPECT_EQ(three->hard_voxels, one->hard_voxels);
  EXPECT_EQ(three->voxels_with_more_points, one->voxels_with_more_points);
}

TEST(VoxelizationThreads, DistinctPointCountIsTheSameForAnyThreadCount) {
  std::vector<Point3f> points = UnevenSphere(100000);
  // Equal under ==, so one point: +0 and -0.
  points.push_back({0.0f, 0.0f, 0.0f});
  points.push_back({-0.0f, 0.0f, -0.0f});
  for (int threads : {1, 2, 3, 4, 8}) {
    EXPECT_EQ(DistinctPointCount(points, threads), 100001) << threads << " threads";
  }
}

// Copies far apart in the cloud (in other blocks of the count's passes), +0 and -0 at its two
// ends, and a cloud of one point given 200k times (one bucket holding every point).
TEST(VoxelizationThreads, DistinctPointCountFindsCopiesAcrossTheCloud) {
  const std::vector<Point3f> base = UnevenSphere(100000);
  std::vector<Point3f> points = {{0.0f, -0.0f, 0.0f}};
  points.insert(points.end(), base.begin(), base.end());
  points.insert(points.end(), base.rbegin(), base.rend());
  points.insert(points.end(), base.begin(), base.begin() + 50000);
  points.push_back({-0.0f, 0.0f, -0.0f});
  const std::vector<Point3f> same(200000, Point3f{0.25f, -1.5f, 3.0f});
  for (int threads : {1, 2, 3, 8}) {
    EXPECT_EQ(DistinctPointCount(points, threads), 100001) << threads << " threads";
    EXPECT_EQ(DistinctPointCount(same, threads), 1) << threads << " threads";
  }
}

TEST(VoxelizationThreads, SortedPointVoxelsIsTheSortedListForAnyThreadCount) {
  const std::vector<Point3f> points = UnevenSphere(150000);
  Box3d box;
  box.min = {-0.9, -1, -1};  // some points outside: clamped into the region
  box.max = {1, 1, 1};
  const double size = 0.013;
  const std::array<int, 3> dims = DataDims(box, size);
  std::vector<int64_t> expected;
  for (const Point3f& p : points) {
    int64_t c[3];
    for (int d = 0; d < 3; ++d) {
      c[d] = std::clamp(static_cast<int64_t>(std::floor((p[d] - box.min[d]) / size)), int64_t{0},
                        int64_t{dims[d]} - 1);
    }
    expected.push_back(c[0] + dims[0] * (c[1] + int64_t{dims[1]} * c[2]));
  }
  std::sort(expected.begin(), expected.end());
  for (int threads : {1, 2, 3, 4}) {
    EXPECT_TRUE(SortedPointVoxels(points, box, size, dims, threads) == expected)
        << threads << " threads";
  }
}

// The voxel of each point, x + nx (y + ny z), sorted: what SortedPointVoxels must return.
std::vector<int64_t> SortedVoxelsOneByOne(const std::vector<Point3f>& points, const Box3d& box,
                                          double size, const std::array<int, 3>& dims) {
  std::vector<int64_t> voxels;
  for (const Point3f& p : points) {
    int64_t c[3];
    for (int d = 0; d < 3; ++d) {
      c[d] = std::clamp(static_cast<int64_t>(std::floor((p[d] - box.min[d]) / size)),
                        int64_t{0}, int64_t{dims[d]} - 1);
    }
    voxels.push_back(c[0] + dims[0] * (c[1] + int64_t{dims[1]} * c[2]));
  }
  std::sort(voxels.begin(), voxels.end());
  return voxels;
}

// Slabs sorted by radix passes: a box four planes deep (a plane a slab, the points above it
// clamped into the top one), each slab tens of thousands of points whose span is one, two or
// three 12-bit digits (planes of 5^2, 501^2 and 4167^2 voxels), many points sharing a voxel;
// and a slab whose points all lie in one voxel.
TEST(VoxelizationThreads, SortedPointVoxelsSortsLargeSlabs) {
  std::vector<Point3f> points = UnevenSphere(150000);
  for (int k = 0; k < 5000; ++k) points.push_back({0.5f, 0.5f, -0.99f});
  for (const double size : {0.5, 0.004, 0.00048}) {
    Box3d box;
    box.min = {-1, -1, -1};
    box.max = {1, 1, -1 + 3.5 * size};
    const std::array<int, 3> dims = DataDims(box, size);
    ASSERT_EQ(dims[2], 4);
    const std::vector<int64_t> expected = SortedVoxelsOneByOne(points, box, size, dims);
    for (int threads : {1, 3}) {
      EXPECT_TRUE(SortedPointVoxels(points, box, size, dims, threads) == expected)
          << "voxel " << size << ", " << threads << " threads";
    }
  }
  const std::vector<Point3f> one_voxel(5000, Point3f{0.25f, 0.25f, 0.25f});
  Box3d box;
  box.min = {0, 0, 0};
  box.max = {1, 1, 0.5};
  const std::array<int, 3> dims = DataDims(box, 0.7);
  EXPECT_TRUE(SortedPointVoxels(one_voxel, box, 0.7, dims) ==
              SortedVoxelsOneByOne(one_voxel, box, 0.7, dims));
}

}  // namespace
}  // namespace membrane
