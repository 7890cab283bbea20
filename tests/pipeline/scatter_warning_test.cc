// Points scattered about their surface by more than a voxel give false handles; the pipeline
// says so, with a voxel size that suits them, and says nothing for clean scans.
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/engine/point_density.h"
#include "core/engine/voxelization.h"
#include "core/pipeline/reconstruction_options.h"
#include "core/pipeline/scatter_warning.h"
#include "core/synth/synthesize.h"
#include "tests/support/in_memory_run.h"
#include "tests/support/uniform_noise.h"

namespace membrane::testing {
namespace {

PointCloud Sphere(double noise) {
  absl::StatusOr<PointCloud> cloud = SynthesizeShape(
      SynthOptions{.shape = "sphere", .points = 50000, .noise = noise, .seed = 3});
  EXPECT_TRUE(cloud.ok()) << cloud.status();
  return cloud.value_or(PointCloud{});
}

ReconstructionReport Reconstruct(const PointCloud& cloud, double voxel_size) {
  ReconstructionOptions options;
  options.voxelize.voxel_size = voxel_size;
  options.surface = SurfaceKind::kCuberille;
  absl::StatusOr<ReconstructionReport> r = ReconstructInMemory(cloud, options);
  EXPECT_TRUE(r.ok()) << r.status();
  return r.value_or(ReconstructionReport{});
}

TEST(ScatterWarning, CleanScanGetsNone) {
  const ReconstructionReport report = Reconstruct(Sphere(0), 0);
  EXPECT_GE(report.density_ratio, kScatteredDensityRatio);
  EXPECT_TRUE(report.warnings.empty());
}

// Radial noise of 0.05 on a unit sphere is more than two formula-(1) voxels: at that size,
// given, the membrane gets a false handle. The warning's voxel size reaches a scan's ratio, and
// there the sphere is a sphere again, without a warning.
TEST(ScatterWarning, NoisySphereIsWarnedAndTheSuggestedSizeMendsItsGenus) {
  const PointCloud cloud = Sphere(0.05);
  const absl::StatusOr<Box3d> box = CheckedBounds(cloud.points);
  ASSERT_TRUE(box.ok());
  const ReconstructionReport report = Reconstruct(cloud, FormulaVoxelSize(*box, cloud.points));
  ASSERT_LT(report.density_ratio, kScatteredDensityRatio);
  ASSERT_EQ(report.warnings.size(), 1u);
  const std::string& w = report.warnings[0];
  EXPECT_NE(w.find("scatter"), std::string::npos) << w;
  EXPECT_NE(w.find("false handles"), std::string::npos) << w;
  const size_t at = w.find("a voxel size of ");
  ASSERT_NE(at, std::string::npos) << w;
  const double suggested = std::stod(w.substr(at + 16));
  EXPECT_GT(suggested, report.voxel_size);
  absl::StatusOr<Box3d> bounds = CheckedBounds(cloud.points);
  ASSERT_TRUE(bounds.ok());
  EXPECT_GE(MeasurePointDensity(cloud.points, *bounds, suggested).ratio(),
            kSuggestedDensityRatio);
  const ReconstructionReport mended = Reconstruct(cloud, suggested);
  EXPECT_EQ(mended.membrane.shells, 1);
  EXPECT_EQ(mended.membrane.genus, std::vector<int>{0});
  EXPECT_TRUE(mended.warnings.empty());
}

// By default the voxel follows the noise (NoiseAwareVoxelSize): the sphere is a sphere, and the
// one warning says why the voxel is coarser than formula (1)'s.
TEST(ScatterWarning, NoisySphereByDefaultGetsAVoxelForItsNoiseAndIsToldSo) {
  const ReconstructionReport report = Reconstruct(Sphere(0.05), 0);
  EXPECT_GT(report.voxel_size, 4 * report.formula_voxel_size);
  EXPECT_GE(report.density_ratio, kScatteredDensityRatio);
  EXPECT_EQ(report.membrane.shells, 1);
  EXPECT_EQ(report.membrane.genus, std::vector<int>{0});
  ASSERT_EQ(report.warnings.size(), 1u);
  EXPECT_NE(report.warnings[0].find("scatter across their surface"), std::string::npos)
      << report.warnings[0];
}

TEST(ScatterWarning, PointsThatNoSizeTriedGathersAreAskedAbout) {
  // Uniform points in a box: 1.25x the voxel gathers them no better.
  const PointCloud cloud = UniformNoise(200000, 7);
  absl::StatusOr<Box3d> bounds = CheckedBounds(cloud.points);
  ASSERT_TRUE(bounds.ok());
  const double l = FormulaVoxelSize(*bounds, cloud.points);
  const PointDensity density = MeasurePointDensity(cloud.points, *bounds, l);
  const std::optional<std::string> w =
      ScatterWarning(cloud.points, *bounds, l, density, CancelToken::Never(), /*size_steps=*/1);
  ASSERT_TRUE(w.has_value());
  EXPECT_NE(w->find("do the points sample one surface?"), std::string::npos) << *w;
}

TEST(ScatterWarning, ACancelledRunStopsMeasuring) {
  const PointCloud cloud = Sphere(0.05);
  absl::StatusOr<Box3d> bounds = CheckedBounds(cloud.points);
  ASSERT_TRUE(bounds.ok());
  CancelToken cancel;
  cancel.Cancel();
  EXPECT_FALSE(ScatterWarning(cloud.points, *bounds, 0.02, PointDensity{100, 10}, cancel));
}

// A scanner that repeats every point fills no voxel with a single one: dense, not scattered,
// although the paper's ratio is then undefined (reported as 0).
TEST(ScatterWarning, EveryPointTwiceIsNotScattered) {
  PointCloud cloud = Sphere(0);
  const size_t n = cloud.points.size();
  for (size_t i = 0; i < n; ++i) cloud.points.push_back(cloud.points[i]);
  const ReconstructionReport report = Reconstruct(cloud, 0);
  EXPECT_EQ(report.density_ratio, 0);
  EXPECT_TRUE(report.warnings.empty());
}

}  // namespace
}  // namespace membrane::testing
