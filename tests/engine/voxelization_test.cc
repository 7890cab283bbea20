#include "core/engine/voxelization.h"

#include <cmath>
#include <limits>

#include "gmock/gmock.h"
#include "gtest/gtest.h"

namespace membrane {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

PointCloud Cube8() {
  PointCloud c;
  for (int i = 0; i < 8; ++i) c.points.push_back({float(i & 1), float((i >> 1) & 1), float(i >> 2)});
  return c;
}

TEST(Voxelization, FormulaOneMatchesThePaper) {
  Box3d box;
  box.max = {2, 3, 4};
  // l = sqrt(2 (6 + 12 + 8) / 52) = 1.
  EXPECT_DOUBLE_EQ(EstimateVoxelSize(box, 52), 1.0);
}

TEST(Voxelization, FormulaOneCountsEachPointOnce) {
  // A cloud given three times over samples its surface no more densely: the formula-(1) voxel
  // (and so the grid and the hard voxels) is the one of the cloud given once.
  std::vector<Point3f> once;
  for (int i = 0; i < 2000; ++i) {
    const double t = 0.37 * i, z = 1.0 - 2.0 * (i + 0.5) / 2000;
    const double r = std::sqrt(1 - z * z);
    once.push_back({float(r * std::cos(t)), float(r * std::sin(t)), float(z)});
  }
  std::vector<Point3f> thrice;
  for (int copy = 0; copy < 3; ++copy) thrice.insert(thrice.end(), once.begin(), once.end());
  EXPECT_EQ(DistinctPointCount(thrice), 2000);
  auto a = Voxelize(once, {});
  auto b = Voxelize(thrice, {});
  ASSERT_TRUE(a.ok() && b.ok());
  EXPECT_EQ(a->grid.voxel_size(), b->grid.voxel_size());
  EXPECT_EQ(a->grid.dims(), b->grid.dims());
  EXPECT_EQ(a->hard_voxels, b->hard_voxels);
}

TEST(Voxelization, GridHasPaddingAndInitialMembraneOnExteriorFaces) {
  VoxelizeOptions o;
  o.voxel_size = 0.25;
  auto v = Voxelize(Cube8().points, o);
  ASSERT_TRUE(v.ok()) << v.status();
  EXPECT_EQ(v->data_dims, (std::array<int, 3>{5, 5, 5}));
  EXPECT_EQ(v->grid.dims(), (std::array<int, 3>{9, 9, 9}));
  EXPECT_TRUE(IsOutside(v->grid.at(Coord{1, 4, 4})));
  EXPECT_EQ(GenerationLabel(v->grid.at(Coord{1, 4, 4})), 0);
  EXPECT_TRUE(IsBoundary(v->grid.at(Coord{2, 4, 4})));
  EXPECT_TRUE(IsInside(v->grid.at(Coord{4, 4, 4})));
  // The eight corners hold points: boundary hard voxels.
  EXPECT_EQ(v->grid.at(Coord{2, 2, 2}), kBoundaryHard);
  EXPECT_EQ(v->grid.at(Coord{6, 6, 6}), kBoundaryHard);
  EXPECT_EQ(v->hard_voxels, 8);
}

TEST(Voxelization, DensityRatioCountsVoxelsWithSeveralPoints) {
  PointCloud c = Cube8();
  c.points.push_back({0.01f, 0.01f, 0.01f});  // a second point in the first corner voxel
  VoxelizeOptions o;
  o.voxel_size = 0.25;
  auto v = Voxelize(c.points, o);
  ASSERT_TRUE(v.ok());
  EXPECT_EQ(v->voxels_with_more_points, 1);
  EXPECT_EQ(v->voxels_with_one_point, 7);
  EXPECT_DOUBLE_EQ(v->density_ratio, 1.0 / 7.0);
}

TEST(Voxelization, GridOverBudgetIsResourceExhaustedNamingGridAndBudget) {
  VoxelizeOptions o;
  o.voxel_size = 0.0001;
  o.voxel_budget = 400'000'000;
  auto v = Voxelize(Cube8().points, o);
  ASSERT_EQ(v.status().code(), absl::StatusCode::kResourceExhausted);
  EXPECT_THAT(v.status().message(), HasSubstr("10005x10005x10005"));
  EXPECT_THAT(v.status().message(), HasSubstr("voxel budget of 4e+08"));
}

TEST(Voxelization, NegativeBudgetIsInvalidArgument) {
  VoxelizeOptions o;
  o.voxel_budget = -1;
  EXPECT_EQ(Voxelize(Cube8().points, o).status().code(), absl::StatusCode::kInvalidArgument);
}

TEST(Voxelization, NoPointsIsInvalidArgument) {
  auto v = Voxelize({}, {});
  ASSERT_EQ(v.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(v.status().message(), HasSubstr("no points"));
}

TEST(Voxelization, OnePointIsInvalidArgument) {
  std::vector<Point3f> p = {{1, 2, 3}};
  auto v = Voxelize(p, {});
  ASSERT_EQ(v.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(v.status().message(), HasSubstr("equal"));
}

TEST(Voxelization, AllPointsEqualIsInvalidArgument) {
  std::vector<Point3f> p(100, Point3f{1, 2, 3});
  auto v = Voxelize(p, {});
  ASSERT_EQ(v.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(v.status().message(), HasSubstr("all 100 points are equal"));
}

TEST(Voxelization, CoplanarPointsAreInvalidArgument) {
  std::vector<Point3f> p;
  for (int i = 0; i < 20; ++i)
    for (int j = 0; j < 20; ++j) p.push_back({float(i), float(j), float(i + j)});  // a tilted plane
  auto v = Voxelize(p, {});
  ASSERT_EQ(v.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(v.status().message(), HasSubstr("coplanar"));
}

TEST(Voxelization, ElongatedCloudsAreNotCoplanar) {
  // A round blob with one stray point 10^5 radii away, and a rod 1000 times longer than it is
  // wide: their covariances are far from singular, only very unequal.
  std::vector<Point3f> blob;
  for (int i = 0; i < 20; ++i)
    for (int j = 0; j < 20; ++j)
      for (int k = 0; k < 20; ++k) blob.push_back({float(i), float(j), float(k)});
  blob.push_back({1e6f, 0, 0});
  EXPECT_TRUE(CheckedBounds(blob).ok()) << CheckedBounds(blob).status();
  std::vector<Point3f> rod;
  for (int i = 0; i < 4000; ++i)
    for (int a = 0; a < 8; ++a)
      rod.push_back({float(i), float(std::cos(a * 0.785398)), float(std::sin(a * 0.785398))});
  EXPECT_TRUE(CheckedBounds(rod).ok()) << CheckedBounds(rod).status();
}

// A unit sphere of `n` points, shifted by `offset` on every axis and scaled by `scale`.
std::vector<Point3f> Sphere(int n, double offset = 0, double scale = 1) {
  std::vector<Point3f> sphere;
  for (int i = 0; i < n; ++i) {
    const double t = 2.399963 * i, z = 1.0 - 2.0 * (i + 0.5) / n;
    const double r = std::sqrt(1 - z * z);
    sphere.push_back({float(scale * (offset + r * std::cos(t))),
                      float(scale * (offset + r * std::sin(t))), float(scale * (offset + z))});
  }
  return sphere;
}

// However far the stray point (up to float32's largest), a sphere is a solid: the voxelizer
// then says what it does see (a grid too coarse to hold one), never "coplanar".
TEST(Voxelization, SpherePlusOneFarPointIsNotCoplanar) {
  for (const float far : {1e3f, 1e7f, 1e20f, 2e38f}) {
    std::vector<Point3f> cloud = Sphere(10000);
    cloud.push_back({far, 0, 0});
    const absl::StatusOr<Box3d> bounds = CheckedBounds(cloud);
    EXPECT_TRUE(bounds.ok()) << far << ": " << bounds.status();
    EXPECT_THAT(Voxelize(cloud, {}).status().message(), Not(HasSubstr("coplanar"))) << far;
  }
}

TEST(Voxelization, PointsOnALineAreCollinear) {
  std::vector<Point3f> p;
  for (int i = 0; i < 50; ++i) p.push_back({float(i), float(2 * i), float(-i)});
  auto v = Voxelize(p, {});
  ASSERT_EQ(v.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(v.status().message(), HasSubstr("the 50 points are collinear"));
}

// Float32 reaches 3.4e38: a cloud whose grid would pass it is told so with its range, not a
// failure of some later stage about an infinite box.
TEST(Voxelization, CoordinatesPastFloatRangeAreInvalidArgumentNamingTheRange) {
  EXPECT_TRUE(Voxelize(Sphere(10000, 0, 1.5e38), {}).ok());
  auto v = Voxelize(Sphere(10000, 0, 2e38), {});
  ASSERT_EQ(v.status().code(), absl::StatusCode::kInvalidArgument) << v.status();
  EXPECT_THAT(v.status().message(), HasSubstr("the coordinates span [-2e+38, 2e+38]"));
  EXPECT_THAT(v.status().message(), HasSubstr("past the +-3.37e+38 that float32 mesh"));
}

TEST(Voxelization, CoordinatesTooFarForFloatPrecisionAreInvalidArgument) {
  // A unit sphere of 50k points: at 1e6 from the origin floats are 0.0625 apart, coarser than
  // its formula-(1) voxel (about 0.02); at 1e3 they are 6e-5 apart.
  for (const double offset : {1e3, 1e6}) {
    std::vector<Point3f> sphere;
    for (int i = 0; i < 50000; ++i) {
      const double t = 2.399963 * i, z = 1.0 - 2.0 * (i + 0.5) / 50000;
      const double r = std::sqrt(1 - z * z);
      sphere.push_back({float(offset + r * std::cos(t)), float(offset + r * std::sin(t)),
                        float(offset + z)});
    }
    auto v = Voxelize(sphere, {});
    if (offset == 1e3) {
      EXPECT_TRUE(v.ok()) << v.status();
    } else {
      ASSERT_EQ(v.status().code(), absl::StatusCode::kInvalidArgument);
      EXPECT_THAT(v.status().message(), HasSubstr("float32 positions are 0.0625 apart"));
      EXPECT_THAT(v.status().message(), HasSubstr("move the cloud near the origin"));
    }
  }
}

TEST(Voxelization, NanAndInfiniteCoordinatesAreCounted) {
  PointCloud c = Cube8();
  c.points.push_back({std::numeric_limits<float>::quiet_NaN(), 0, 0});
  c.points.push_back({0, std::numeric_limits<float>::infinity(), 0});
  auto v = Voxelize(c.points, {});
  ASSERT_EQ(v.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(v.status().message(), HasSubstr("2 of 10 points have NaN or infinite"));
}

TEST(Voxelization, NonPositiveVoxelSizeIsInvalidArgument) {
  VoxelizeOptions o;
  o.voxel_size = -1;
  auto v = Voxelize(Cube8().points, o);
  ASSERT_EQ(v.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(v.status().message(), HasSubstr("voxel size -1"));
}

// The pipeline's grid planning checks the points once and passes the box on: Voxelize given it
// makes the grid it makes from its own check, with the formula-(1) voxel and a given one.
TEST(Voxelization, GivenCheckedBoundsGiveTheSameGrid) {
  std::vector<Point3f> points;
  for (int i = 0; i < 5000; ++i) {
    const double t = 2.399963 * i, z = 1.0 - 2.0 * (i + 0.5) / 5000;
    const double r = std::sqrt(1 - z * z);
    points.push_back({float(0.3 + 1.7 * r * std::cos(t)), float(-2 + r * std::sin(t)),
                      float(5 + 0.8 * z)});
  }
  const absl::StatusOr<Box3d> bounds = CheckedBounds(points);
  ASSERT_TRUE(bounds.ok()) << bounds.status();
  for (const double voxel_size : {0.0, 0.07}) {
    const absl::StatusOr<Voxelization> own = Voxelize(points, {.voxel_size = voxel_size});
    const absl::StatusOr<Voxelization> given =
        Voxelize(points, {.voxel_size = voxel_size, .checked_bounds = *bounds});
    ASSERT_TRUE(own.ok()) << own.status();
    ASSERT_TRUE(given.ok()) << given.status();
    EXPECT_EQ(given->grid.voxel_size(), own->grid.voxel_size()) << voxel_size;
    EXPECT_EQ(given->grid.dims(), own->grid.dims()) << voxel_size;
    EXPECT_EQ(given->grid.origin(), own->grid.origin()) << voxel_size;
    EXPECT_TRUE(given->grid.states() == own->grid.states()) << voxel_size;
    EXPECT_EQ(given->bounds.min, own->bounds.min) << voxel_size;
    EXPECT_EQ(given->bounds.max, own->bounds.max) << voxel_size;
    EXPECT_EQ(given->data_dims, own->data_dims) << voxel_size;
    EXPECT_EQ(given->hard_voxels, own->hard_voxels) << voxel_size;
    EXPECT_EQ(given->density_ratio, own->density_ratio) << voxel_size;
  }
}

}  // namespace
}  // namespace membrane
