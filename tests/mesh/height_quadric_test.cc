#include "core/mesh/height_quadric.h"

#include <cmath>
#include <vector>

#include "gtest/gtest.h"

namespace membrane {
namespace {

struct UVH {
  double u, v, h, w;
};

HeightFieldSums SumsOf(const std::vector<UVH>& points) {
  HeightFieldSums s;
  for (const UVH& p : points) {
    for (int i = 0; i <= 4; ++i)
      for (int j = 0; i + j <= 4; ++j)
        s.uv[HeightFieldSums::Index(i, j)] += p.w * std::pow(p.u, i) * std::pow(p.v, j);
    for (int i = 0; i <= 2; ++i)
      for (int j = 0; i + j <= 2; ++j)
        s.huv[HeightFieldSums::Index(i, j)] += p.w * p.h * std::pow(p.u, i) * std::pow(p.v, j);
    s.hh += p.w * p.h * p.h;
    ++s.count;
  }
  return s;
}

// Points of h(u, v) with these coefficients (f, d, e, a, b, c) on a grid over [-r, r]^2,
// Gaussian-weighted like the fit's.
std::vector<UVH> Sampled(const std::array<double, 6>& k, double r, double v_scale = 1) {
  std::vector<UVH> points;
  for (int i = -8; i <= 8; ++i)
    for (int j = -8; j <= 8; ++j) {
      const double u = r * i / 8, v = v_scale * r * j / 8;
      const double h = k[0] + k[1] * u + k[2] * v + k[3] * u * u + k[4] * u * v + k[5] * v * v;
      points.push_back({u, v, h, std::exp(-(u * u + v * v) / 2)});
    }
  return points;
}

TEST(HeightQuadric, RecoversTheQuadricThePointsLieOn) {
  const std::array<double, 6> k = {0.12, 0.2, -0.1, 0.3, -0.2, 0.15};
  const auto q = FitHeightQuadric(SumsOf(Sampled(k, 2)), {});
  ASSERT_TRUE(q.has_value());
  for (int i = 0; i < 6; ++i) EXPECT_NEAR(q->coefficients[i], k[i], 1e-9) << i;
  EXPECT_NEAR(q->height(), 0.12, 1e-9);
}

TEST(HeightQuadric, HeightAtTheVertexIsTheSphereNotItsChord) {
  // A sphere of radius 8 voxels seen from a vertex 0.2 voxels outside it: the points lie
  // below the vertex by 0.2 at u = v = 0 and bend away; a plane through them would sit near
  // their mean height, inside the sphere.
  const double radius = 8, above = 0.2;
  std::vector<UVH> points;
  for (int i = -8; i <= 8; ++i)
    for (int j = -8; j <= 8; ++j) {
      const double u = 2.0 * i / 8, v = 2.0 * j / 8;
      if (u * u + v * v > 4) continue;
      const double h = std::sqrt(radius * radius - u * u - v * v) - radius - above;
      points.push_back({u, v, h, std::exp(-(u * u + v * v) / 2)});
    }
  const HeightFieldSums sums = SumsOf(points);
  const auto q = FitHeightQuadric(sums, {});
  ASSERT_TRUE(q.has_value());
  EXPECT_NEAR(q->height(), -above, 2e-3);
  const auto plane = sums.PlaneSums().Fit();
  ASSERT_TRUE(plane.has_value());
  EXPECT_LT(plane->centroid[2], -above - 0.05);  // the chord lies inside
}

TEST(HeightQuadric, PlaneSumsAreTheSumsOfThePoints) {
  const std::vector<UVH> points = Sampled({0.1, 0.3, 0, 0.05, 0, 0}, 1.5);
  PlaneFitAccumulator want;
  for (const UVH& p : points) want.Add({p.u, p.v, p.h}, p.w);
  const auto a = SumsOf(points).PlaneSums().Fit(), b = want.Fit();
  ASSERT_TRUE(a.has_value() && b.has_value());
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(a->centroid[k], b->centroid[k], 1e-12);
    EXPECT_NEAR(a->normal[k], b->normal[k], 1e-9);
  }
}

TEST(HeightQuadric, RefusesWhatItCannotTrust) {
  // A strip of points (all near v = 0): the v terms are extrapolated.
  EXPECT_FALSE(FitHeightQuadric(SumsOf(Sampled({0, 0, 0, 0.1, 0, 0}, 2, 0.05)), {}));
  // The vertex beyond the points' footprint: points only at u in [1, 3].
  std::vector<UVH> aside;
  for (const UVH& p : Sampled({0, 0, 0, 0.1, 0, 0}, 2))
    if (p.u >= 0) aside.push_back({p.u + 1, p.v, 0.1 * (p.u + 1) * (p.u + 1), p.w});
  EXPECT_FALSE(FitHeightQuadric(SumsOf(aside), {}));
  // Steeper than 45 degrees: the frame is not the surface's.
  EXPECT_FALSE(FitHeightQuadric(SumsOf(Sampled({0, 1.5, 0, 0, 0, 0}, 2)), {}));
  // Bent sharper than the voxels resolve.
  EXPECT_FALSE(FitHeightQuadric(SumsOf(Sampled({0, 0, 0, 2, 0, 0}, 2)), {}));
  // No weight.
  EXPECT_FALSE(FitHeightQuadric(HeightFieldSums{}, {}));
  // Within every limit.
  EXPECT_TRUE(FitHeightQuadric(SumsOf(Sampled({0, 0.5, 0, 0.5, 0, 0}, 2)), {}));
}

}  // namespace
}  // namespace membrane
