#include "core/mesh/crease_fit.h"

#include <cmath>
#include <functional>
#include <optional>
#include <random>
#include <vector>

#include "core/mesh/height_quadric.h"
#include "gtest/gtest.h"

namespace membrane {
namespace {

// Points on a 0.25-voxel lattice within 2 voxels of the vertex, on h = height(u, v) plus
// Gaussian noise of `noise` voxels, weighted as the fit weighs them (sigma 1 voxel across).
std::vector<FramePoint> CreaseSample(const std::function<double(double, double)>& height,
                                     double noise = 0, uint64_t seed = 1) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> gauss(0, 1);
  std::vector<FramePoint> points;
  for (double u = -2; u <= 2; u += 0.25)
    for (double v = -2; v <= 2; v += 0.25) {
      const double h = height(u, v) + noise * gauss(rng);
      if (u * u + v * v + h * h > 4) continue;
      points.push_back({u, v, h, std::exp(-(u * u + v * v) / 2)});
    }
  return points;
}

HeightFieldSums CreaseSums(const std::vector<FramePoint>& points) {
  HeightFieldSums s;
  for (const FramePoint& p : points) {
    for (int d = 0; d <= 4; ++d)
      for (int j = 0; j <= d; ++j)
        s.uv[HeightFieldSums::Index(d - j, j)] += p.w * std::pow(p.u, d - j) * std::pow(p.v, j);
    for (int d = 0; d <= 2; ++d)
      for (int j = 0; j <= d; ++j)
        s.huv[HeightFieldSums::Index(d - j, j)] +=
            p.w * p.h * std::pow(p.u, d - j) * std::pow(p.v, j);
    s.hh += p.w * p.h * p.h;
    ++s.count;
  }
  return s;
}

std::optional<CreaseFit> FitCreaseOf(const std::vector<FramePoint>& points,
                                     const CreaseLimits& limits = {}) {
  const HeightFieldSums sums = CreaseSums(points);
  const std::optional<HeightQuadric> q = SolveHeightQuadric(sums);
  if (!q) return std::nullopt;
  return FitCrease(points, *q, std::sqrt(QuadricMeanSquareResidual(sums, *q)), limits);
}

TEST(CreaseFit, QuadricResidualIsTheMeanSquareOfTheHeightsAboutIt) {
  const auto points = CreaseSample([](double u, double v) { return 0.1 * u - 0.2 * v * v; }, 0.05);
  const HeightFieldSums sums = CreaseSums(points);
  const auto q = SolveHeightQuadric(sums);
  ASSERT_TRUE(q);
  double direct = 0, weight = 0;
  for (const FramePoint& p : points) {
    const auto& c = q->coefficients;
    const double r = p.h - (c[0] + c[1] * p.u + c[2] * p.v + c[3] * p.u * p.u + c[4] * p.u * p.v +
                            c[5] * p.v * p.v);
    direct += p.w * r * r;
    weight += p.w;
  }
  EXPECT_NEAR(QuadricMeanSquareResidual(sums, *q), direct / weight, 1e-9);
}

// A right-angled ridge along v through u = 0.3: the vertex goes onto the edge.
TEST(CreaseFit, ARidgeNearTheVertexPutsItOnTheEdge) {
  const auto fit = FitCreaseOf(CreaseSample([](double u, double) { return -std::fabs(u - 0.3); }));
  ASSERT_TRUE(fit);
  EXPECT_TRUE(fit->ridge);
  EXPECT_TRUE(fit->on_line);
  EXPECT_LT(fit->rms, 1e-6);
  EXPECT_NEAR(fit->target[0], 0.3, 1e-6);
  EXPECT_NEAR(fit->target[1], 0.0, 1e-6);
  EXPECT_NEAR(fit->target[2], 0.0, 1e-6);
}

// A valley of 45 degrees a side, its edge skew to the frame: the upper envelope.
TEST(CreaseFit, AValleyIsTheUpperEnvelope) {
  const double cu = std::cos(0.6), cv = std::sin(0.6);
  const auto fit = FitCreaseOf(
      CreaseSample([&](double u, double v) { return std::fabs(cu * u + cv * v + 0.2); }));
  ASSERT_TRUE(fit);
  EXPECT_FALSE(fit->ridge);
  ASSERT_TRUE(fit->on_line);
  // The edge's point nearest the vertex: (-0.2 cu, -0.2 cv, 0).
  EXPECT_NEAR(fit->target[0], -0.2 * cu, 1e-6);
  EXPECT_NEAR(fit->target[1], -0.2 * cv, 1e-6);
  EXPECT_NEAR(fit->target[2], 0.0, 1e-6);
}

// An edge 0.9 voxel away: the vertex stays off it, on its own plane's height.
TEST(CreaseFit, AnEdgeFartherThanTheSnapDistanceGivesThePlaneHeight) {
  const auto fit =
      FitCreaseOf(CreaseSample([](double u, double) { return 0.2 - std::fabs(u - 0.9); }));
  ASSERT_TRUE(fit);
  EXPECT_FALSE(fit->on_line);
  EXPECT_NEAR(fit->target[0], 0.0, 1e-12);
  EXPECT_NEAR(fit->target[2], 0.2 - 0.9, 1e-6);
}

TEST(CreaseFit, NoisyRidgeStillFits) {
  const auto fit = FitCreaseOf(CreaseSample([](double u, double) { return -std::fabs(u); }, 0.03));
  ASSERT_TRUE(fit);
  EXPECT_TRUE(fit->on_line);
  EXPECT_LT(std::fabs(fit->target[0]), 0.1);
  EXPECT_LT(std::fabs(fit->target[2]), 0.1);
}

// Smooth surfaces that bend within the voxel's reach are the quadric's: a sphere of 3 voxels,
// a cylinder of 2, a saddle, and noise on a plane.
TEST(CreaseFit, SmoothSurfacesAndNoiseAreNoCrease) {
  const std::vector<std::function<double(double, double)>> shapes = {
      [](double u, double v) { return std::sqrt(std::max(0.0, 9 - u * u - v * v)) - 3; },
      [](double u, double) { return std::sqrt(std::max(0.0, 4 - u * u)) - 2; },
      [](double u, double v) { return 0.3 * (u * u - v * v); },
      [](double, double) { return 0.0; },
  };
  for (size_t i = 0; i < shapes.size(); ++i) {
    for (uint64_t seed = 1; seed <= 5; ++seed) {
      const auto fit = FitCreaseOf(CreaseSample(shapes[i], 0.08, seed));
      EXPECT_FALSE(fit) << "shape " << i << " seed " << seed << ": rms " << fit->rms;
    }
  }
}

// A shallow fold (10 degrees between the planes) is below the angle the limits take.
TEST(CreaseFit, AShallowFoldIsLeftToTheQuadric) {
  const double slope = std::tan(5 * M_PI / 180);
  CreaseLimits limits;
  limits.min_quadric_rms = 0;
  EXPECT_FALSE(
      FitCreaseOf(CreaseSample([&](double u, double) { return -slope * std::fabs(u); }), limits));
}

}  // namespace
}  // namespace membrane
