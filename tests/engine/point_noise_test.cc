// MeasurePointNoise reads range noise as itself and a clean surface, curved or in two close
// sheets, as nearly none; NoiseAwareVoxelSize keeps formula (1)'s size unless the noise is over
// kVoxelNoiseShare of it.
#include "core/engine/point_noise.h"

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "core/engine/voxelization.h"
#include "gtest/gtest.h"

namespace membrane {
namespace {

// `n` points drawn uniformly on the square [0, side)^2 of the plane z = z0, each moved along z by
// a Gaussian of deviation `sigma`.
void AddNoisyPlane(int n, double side, double z0, double sigma, std::mt19937& rng,
                   std::vector<Point3f>& points) {
  std::uniform_real_distribution<double> u(0, side);
  std::normal_distribution<double> g(0, 1);
  for (int i = 0; i < n; ++i) {
    const double z = sigma > 0 ? z0 + sigma * g(rng) : z0;
    points.push_back({static_cast<float>(u(rng)), static_cast<float>(u(rng)),
                      static_cast<float>(z)});
  }
}

// Formula (1)'s voxel for `n` points on the unit square (whose box is flat: lx ly = 1).
double SquareVoxel(int n) { return EstimateVoxelSize(Box3d{{0, 0, 0}, {1, 1, 0}}, n); }

// The noise of `points` read in cubes 4 voxels of size `l` wide, in those voxels; -1 when too
// few cubes had enough points to fit.
double NoiseInVoxels(const std::vector<Point3f>& points, double l) {
  const PointNoise noise = MeasurePointNoise(points, *CheckedBounds(points), 2 * l);
  return noise.fitted_boxes >= kNoiseMinFittedBoxes ? noise.sigma / l : -1;
}

TEST(PointNoiseTest, ReadsRangeNoiseOnAPlaneAsItself) {
  for (const double share : {0.05, 0.2, 0.5}) {
    std::mt19937 rng(7);
    std::vector<Point3f> points;
    const double l = SquareVoxel(200000);
    AddNoisyPlane(200000, 1.0, 0.5, share * l, rng, points);
    // Within 15%: at half a voxel the 2-voxel cube cuts the Gaussian's tails at 4 deviations.
    EXPECT_NEAR(NoiseInVoxels(points, l), share, 0.15 * share) << "noise of " << share << " voxel";
  }
}

// The quadric takes up curvature: a clean sphere 20 voxels in radius reads under 2% of a voxel,
// where the plane's spread over the same cubes is about 6%.
TEST(PointNoiseTest, ACleanSphereReadsNearlyNone) {
  std::mt19937 rng(3);
  std::normal_distribution<double> g(0, 1);
  std::vector<Point3f> points;
  for (int i = 0; i < 100000; ++i) {
    const double x = g(rng), y = g(rng), z = g(rng);
    const double r = std::sqrt(x * x + y * y + z * z);
    points.push_back({static_cast<float>(x / r), static_cast<float>(y / r),
                      static_cast<float>(z / r)});
  }
  const double l = FormulaVoxelSize(*CheckedBounds(points), points);
  ASSERT_GT(1 / l, 15);
  const double noise = NoiseInVoxels(points, l);
  EXPECT_GE(noise, 0);
  EXPECT_LT(noise, 0.02);
}

// Two clean sheets 3 voxels apart (a thin part) do not share a 4-voxel cube centred on either.
TEST(PointNoiseTest, TwoSheetsThreeVoxelsApartReadClean) {
  std::mt19937 rng(5);
  std::vector<Point3f> points;
  // Each sheet is sampled as densely as one sheet alone at formula (1)'s voxel.
  const double l = SquareVoxel(100000);
  AddNoisyPlane(100000, 1.0, 0.0, 0, rng, points);
  AddNoisyPlane(100000, 1.0, 3 * l, 0, rng, points);
  const double noise = NoiseInVoxels(points, l);
  EXPECT_GE(noise, 0);
  EXPECT_LT(noise, 0.01);
}

TEST(PointNoiseTest, TooFewPointsGiveNoEstimate) {
  std::mt19937 rng(1);
  std::vector<Point3f> points;
  AddNoisyPlane(200, 1.0, 0.5, 0.01, rng, points);
  const Box3d bounds = *CheckedBounds(points);
  // Cubes of a hundredth of the side hold a point or two each.
  const PointNoise noise = MeasurePointNoise(points, bounds, 0.005);
  EXPECT_LT(noise.fitted_boxes, kNoiseMinFittedBoxes);
  EXPECT_EQ(noise.sigma, 0);
}

// Points piled on one spot fill their cubes and cost a lookup each after that; the pile reads
// as no surface at all (no plane to fit) and the plane below it as its own slight noise.
TEST(PointNoiseTest, APileOfEqualPointsIsNotFitted) {
  std::mt19937 rng(2);
  std::vector<Point3f> points;
  AddNoisyPlane(50000, 1.0, 0.5, 0.001, rng, points);
  points.insert(points.end(), 200000, Point3f{0.5f, 0.5f, 0.6f});
  const Box3d bounds = *CheckedBounds(points);
  const PointNoise noise = MeasurePointNoise(points, bounds, 0.02);
  ASSERT_GE(noise.fitted_boxes, kNoiseMinFittedBoxes);
  EXPECT_NEAR(noise.sigma, 0.001, 0.00015);
}

TEST(PointNoiseTest, AFiredTokenGivesNoEstimate) {
  std::mt19937 rng(4);
  std::vector<Point3f> points;
  AddNoisyPlane(100000, 1.0, 0.5, 0.01, rng, points);
  const Box3d bounds = *CheckedBounds(points);
  CancelToken cancel;
  cancel.Cancel();
  const PointNoise noise = MeasurePointNoise(points, bounds, 0.02, cancel);
  EXPECT_EQ(noise.fitted_boxes, 0);
  EXPECT_EQ(noise.sigma, 0);
}

TEST(PointNoiseTest, TheVoxelGrowsOnlyPastTheNoiseShare) {
  EXPECT_EQ(NoiseAwareVoxelSize(1.0, PointNoise{}), 1.0);
  EXPECT_EQ(NoiseAwareVoxelSize(1.0, PointNoise{.sigma = kVoxelNoiseShare, .fitted_boxes = 99}),
            1.0);
  EXPECT_DOUBLE_EQ(
      NoiseAwareVoxelSize(1.0, PointNoise{.sigma = 3 * kVoxelNoiseShare, .fitted_boxes = 99}),
      3.0);
}

TEST(PointNoiseTest, ARaisedVoxelIsOneOverAComputedFormulaOneSize) {
  EXPECT_TRUE(VoxelRaisedForNoise(1.0, 1.5));
  EXPECT_FALSE(VoxelRaisedForNoise(1.0, 1.0));
  // A given size records no formula-(1) size.
  EXPECT_FALSE(VoxelRaisedForNoise(0.0, 1.5));
}

}  // namespace
}  // namespace membrane
