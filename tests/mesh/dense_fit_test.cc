// The fit on a dense cloud (point_fitting.h, FitOptions::dense_points_per_vertex): the points
// merged into cell means (point_cell_means.h), the weighed sums over means and their counts
// (near_point_sums.h), and the fitted surface against the fit over every point.
#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <map>
#include <utility>
#include <random>
#include <vector>

#include "core/mesh/near_point_sums.h"
#include "core/mesh/point_cell_means.h"
#include "core/mesh/point_fitting.h"
#include "core/mesh/point_row_grid.h"
#include "core/mesh/smooth_surface.h"
#include "gtest/gtest.h"
#include "tests/mesh/surface_expectations.h"
#include "tests/mesh/test_grids.h"

namespace membrane {
namespace {

using namespace membrane::testing;

constexpr double kNever = std::numeric_limits<double>::infinity();

// A sphere of radius 11 voxels (voxel 0.05) sampled with `count` points, each moved along its
// radius by Gaussian noise of `noise` voxels: a scan's fuzzy skin.
struct NoisySphere {
  static constexpr double kVoxel = 0.05;
  static constexpr double kRadius = 11 * kVoxel;
  const std::array<double, 3> centre = {16 * kVoxel + 0.013, 16 * kVoxel - 0.007,
                                        16 * kVoxel + 0.004};
  std::vector<Point3f> points;
  VoxelGrid grid;

  NoisySphere(int count, double noise) {
    points = SpherePoints(count, centre, kRadius, 11);
    std::mt19937 rng(12);
    std::normal_distribution<double> offset(0, noise * kVoxel);
    for (Point3f& p : points) {
      double d[3], len = 0;
      for (int k = 0; k < 3; ++k) {
        d[k] = p[k] - centre[k];
        len += d[k] * d[k];
      }
      const double scale = 1 + offset(rng) / std::sqrt(len);
      for (int k = 0; k < 3; ++k) p[k] = static_cast<float>(centre[k] + scale * d[k]);
    }
    grid = SampledSphereGrid(32, kVoxel, centre, kRadius, points);
  }
};

TriangleMesh Fit(const NoisySphere& s, double dense_points_per_vertex, int threads,
                 FitStats* fit = nullptr) {
  SmoothSurfaceOptions options;
  options.fit_options.dense_points_per_vertex = dense_points_per_vertex;
  options.fit_options.threads = threads;
  SmoothSurfaceStats stats;
  absl::StatusOr<TriangleMesh> mesh = SmoothSurface(s.grid, s.points, options, &stats);
  EXPECT_TRUE(mesh.ok()) << mesh.status();
  if (fit != nullptr) *fit = stats.fit;
  return mesh.ok() ? *std::move(mesh) : TriangleMesh{};
}

TEST(PointCellMeans, CountsEveryPointOnceAndKeepsLonePoints) {
  std::mt19937 rng(4);
  std::uniform_real_distribution<float> u(0, 1);
  std::vector<Point3f> points(5000);
  for (Point3f& p : points) p = {u(rng), u(rng), 0.05f * u(rng)};
  // One point alone, far from the others: its sub-cell's mean is itself.
  points.push_back({3.1f, 2.7f, 1.3f});
  const PointRowGrid grid(points, 0.3);
  const PointCellMeans m = MeanPerSubCell(grid, 3);
  ASSERT_EQ(m.means.size(), m.counts.size());
  double total = 0;
  for (float c : m.counts) {
    EXPECT_EQ(c, std::floor(c));
    EXPECT_GE(c, 1);
    total += c;
  }
  EXPECT_EQ(total, static_cast<double>(points.size()));
  EXPECT_LT(m.means.size(), points.size() / 4);
  int lone = 0;
  for (size_t i = 0; i < m.means.size(); ++i)
    lone += m.counts[i] == 1 && m.means[i] == points.back();
  EXPECT_EQ(lone, 1);
}

TEST(PointCellMeans, EachSubCellsPointsGiveItsMean) {
  // Sub-cells of 0.1 in cells of 0.3, against the points grouped by the sub-cell of the box's
  // corner that holds them, summed in input order (a cell stores its points in that order).
  std::mt19937 rng(8);
  std::uniform_real_distribution<float> u(0, 1);
  std::vector<Point3f> points(20000);
  for (Point3f& p : points) p = {u(rng), u(rng), 0.3f * u(rng)};
  const PointRowGrid grid(points, 0.3);
  ASSERT_EQ(grid.cell(), 0.3);
  std::map<std::array<int64_t, 3>, std::pair<std::array<double, 3>, int>> groups;
  for (const Point3f& p : points) {
    std::array<int64_t, 3> key;
    for (int k = 0; k < 3; ++k)
      key[k] = static_cast<int64_t>(std::floor((p[k] - grid.origin()[k]) * (3 / 0.3)));
    auto& [sum, count] = groups[key];
    for (int k = 0; k < 3; ++k) sum[k] += p[k];
    ++count;
  }
  std::vector<std::pair<Point3f, float>> want, got;
  for (const auto& [key, group] : groups) {
    const double n = group.second;
    want.push_back({{static_cast<float>(group.first[0] / n), static_cast<float>(group.first[1] / n),
                     static_cast<float>(group.first[2] / n)},
                    static_cast<float>(n)});
  }
  const PointCellMeans m = MeanPerSubCell(grid, 3);
  for (size_t i = 0; i < m.means.size(); ++i) got.push_back({m.means[i], m.counts[i]});
  std::sort(want.begin(), want.end());
  std::sort(got.begin(), got.end());
  EXPECT_EQ(got, want);
}

TEST(PointCellMeans, TheSameMeansOnAnyThreadCount) {
  const NoisySphere s(100000, 0.15);
  const PointCellMeans one = MeanPerSubCell(PointRowGrid(s.points, 2 * s.kVoxel, 1), 3);
  for (int threads : {2, 3}) {
    const PointCellMeans more = MeanPerSubCell(PointRowGrid(s.points, 2 * s.kVoxel, threads), 3);
    EXPECT_TRUE(more.means == one.means) << threads;
    EXPECT_TRUE(more.counts == one.counts) << threads;
  }
}

TEST(NearPointSums, MeansWeighedByTheirCountsSumAsTheirPointsRepeated) {
  // Each weighted point against that many copies of it: the same weighted sums and counts up
  // to float's rounding, in the plane sums and the frame sums.
  std::mt19937 rng(9);
  std::uniform_real_distribution<float> u(-2, 2), n(-0.1f, 0.1f);
  std::uniform_int_distribution<int> copies(1, 9);
  std::vector<Point3f> means(3000), repeated;
  std::vector<float> counts(means.size());
  for (size_t i = 0; i < means.size(); ++i) {
    means[i] = {u(rng), u(rng), n(rng)};
    counts[i] = static_cast<float>(copies(rng));
    for (int k = 0; k < counts[i]; ++k) repeated.push_back(means[i]);
  }
  const double radius = 0.6;
  const PointRowGrid weighted(means, radius / 2, 1, PointRowGrid::Limits(), counts);
  const PointRowGrid plain(repeated, radius / 2);
  for (int q = 0; q < 100; ++q) {
    NearPointWeights w;
    w.origin = {0.7f * u(rng), 0.7f * u(rng), n(rng)};
    w.radius2 = static_cast<float>(radius * radius);
    w.inv_2s2 = 1.0f / (2 * 0.3f * 0.3f);
    w.inv_2n2 = 1.0f / (2 * 0.18f * 0.18f);
    w.normal = {0.1f, -0.2f, std::sqrt(1.0f - 0.05f)};
    const NearPointResult a = WeighNearPoints(weighted, radius, w);
    const NearPointResult b = WeighNearPoints(plain, radius, w);
    ASSERT_EQ(a.count, b.count) << q;
    const double tol = 1e-5 * b.acc.weight() + 1e-12;
    EXPECT_NEAR(a.acc.weight(), b.acc.weight(), tol);
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(a.acc.WeightedSum()[k], b.acc.WeightedSum()[k], tol * radius);

    FrameWeights f;
    f.origin = w.origin;
    f.axes = {{{1 / 0.3f, 0, 0}, {0, 1 / 0.3f, 0}, {0, 0, 1 / 0.3f}}};
    f.radius2 = 4;
    f.inv_2s2 = 0.5f;
    f.inv_2n2 = 1.4f;
    const HeightFieldSums fa = WeighNearPointsInFrame(weighted, radius, f);
    const HeightFieldSums fb = WeighNearPointsInFrame(plain, radius, f);
    ASSERT_EQ(fa.count, fb.count) << q;
    for (int k = 0; k < 15; ++k)
      EXPECT_NEAR(fa.uv[k], fb.uv[k], 1e-5 * fb.weight() * 16 + 1e-12) << q << " " << k;
    for (int k = 0; k < 6; ++k) EXPECT_NEAR(fa.huv[k], fb.huv[k], 1e-5 * fb.weight() * 8 + 1e-12);
  }
}

TEST(DenseFit, CellMeansPlaceTheVerticesWhereEveryPointDoes) {
  // About 55 points a vertex with noise of 0.15 voxel: the fits over cell means and over every
  // point place the vertices at the same heights above the sphere (90% within 0.02 voxel of
  // each other), as close to it on average, and hold as few off it.
  const NoisySphere s(150000, 0.15);
  FitStats all_stats, merged_stats;
  const TriangleMesh all = Fit(s, kNever, 2, &all_stats);
  const TriangleMesh merged = Fit(s, FitOptions().dense_points_per_vertex, 2, &merged_stats);
  EXPECT_EQ(all_stats.weighed_points, static_cast<int64_t>(s.points.size()));
  EXPECT_LT(merged_stats.weighed_points * 10, all_stats.weighed_points);
  ASSERT_EQ(all.faces, merged.faces);
  ASSERT_EQ(all.vertices.size(), merged.vertices.size());
  // Heights above the sphere, in voxels: the fit moves a vertex along its normal. A few
  // percent of the vertices of either fit are held where the surface nets put them (a move
  // refused or backed off for a crossing), which move follows the other moves: the heights are
  // compared at their 90th percentile, and those off the sphere by more than 0.1 voxel counted.
  const auto height = [&](const Point3f& p) {
    double d2 = 0;
    for (int k = 0; k < 3; ++k) d2 += (p[k] - s.centre[k]) * (p[k] - s.centre[k]);
    return (std::sqrt(d2) - s.kRadius) / s.kVoxel;
  };
  std::vector<double> apart;
  double off_all = 0, off_merged = 0;
  int held_all = 0, held_merged = 0;
  for (size_t v = 0; v < all.vertices.size(); ++v) {
    const double a = height(all.vertices[v]), m = height(merged.vertices[v]);
    apart.push_back(std::fabs(a - m));
    off_all += std::fabs(a);
    off_merged += std::fabs(m);
    held_all += std::fabs(a) > 0.1;
    held_merged += std::fabs(m) > 0.1;
  }
  std::sort(apart.begin(), apart.end());
  const double n = static_cast<double>(all.vertices.size());
  const double p50 = apart[apart.size() / 2], p90 = apart[apart.size() * 9 / 10];
  std::cout << "vertices " << n << ", heights apart: median " << p50 << ", 90th percentile "
            << p90 << " voxel; off the sphere: every point " << off_all / n << ", means "
            << off_merged / n << " voxel; over 0.1 voxel off: " << held_all << ", "
            << held_merged << "\n";
  EXPECT_LT(p50, 0.005);
  EXPECT_LT(p90, 0.02);
  EXPECT_LT(off_merged / n, off_all / n + 0.002);
  EXPECT_LE(held_merged, held_all + held_all / 5 + 5);
  ExpectValidSurface(merged, 1, {0});
}

TEST(DenseFit, TheSameBytesOnOneAndThreeThreads) {
  const NoisySphere s(150000, 0.15);
  FitStats one_stats, three_stats;
  const TriangleMesh one = Fit(s, FitOptions().dense_points_per_vertex, 1, &one_stats);
  const TriangleMesh three = Fit(s, FitOptions().dense_points_per_vertex, 3, &three_stats);
  EXPECT_LT(one_stats.weighed_points * 10, static_cast<int64_t>(s.points.size()));
  EXPECT_EQ(one_stats.weighed_points, three_stats.weighed_points);
  EXPECT_EQ(one.faces, three.faces);
  EXPECT_TRUE(one.vertices == three.vertices);
}

TEST(DenseFit, CloudsBelowTheDensityWeighEveryPoint) {
  // About 2 points a vertex, as the 100k-point clouds hold: every point is weighed.
  const NoisySphere s(3000, 0.15);
  FitStats stats;
  Fit(s, FitOptions().dense_points_per_vertex, 1, &stats);
  EXPECT_EQ(stats.weighed_points, static_cast<int64_t>(s.points.size()));
}

}  // namespace
}  // namespace membrane
