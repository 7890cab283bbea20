#include "core/mesh/near_point_sums.h"

#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "absl/types/span.h"
#include "core/mesh/fast_exp.h"
#include "gtest/gtest.h"

namespace membrane {
namespace {

// The same sums in double, point by point: what WeighNearPoints replaces.
struct Reference {
  double w = 0, s[3] = {0, 0, 0}, s2[6] = {0, 0, 0, 0, 0, 0};
  int count = 0;
};

Reference Brute(const std::vector<Point3f>& points, const NearPointWeights& q) {
  Reference r;
  for (const Point3f& p : points) {
    const double d[3] = {double(p[0]) - q.origin[0], double(p[1]) - q.origin[1],
                         double(p[2]) - q.origin[2]};
    const double d2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    if (d2 > q.radius2) continue;
    const double dn = d[0] * q.normal[0] + d[1] * q.normal[1] + d[2] * q.normal[2];
    const double w = std::exp(-(d2 - dn * dn) * q.inv_2s2 - dn * dn * q.inv_2n2);
    ++r.count;
    r.w += w;
    for (int k = 0; k < 3; ++k) r.s[k] += w * d[k];
    const int ij[6][2] = {{0, 0}, {0, 1}, {0, 2}, {1, 1}, {1, 2}, {2, 2}};
    for (int k = 0; k < 6; ++k) r.s2[k] += w * d[ij[k][0]] * d[ij[k][1]];
  }
  return r;
}

TEST(NearPointSums, MatchesTheDoubleSumsPointByPoint) {
  // A noisy sheet through random query points, with anisotropic and isotropic weights.
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(-4, 4), noise(-0.05f, 0.05f);
  std::vector<Point3f> points(20000);
  for (Point3f& p : points) p = {u(rng), u(rng), 0.1f * u(rng) + noise(rng)};
  const double radius = 0.5;
  const PointRowGrid grid(points, radius / 2);
  for (int q = 0; q < 200; ++q) {
    NearPointWeights w;
    w.origin = {u(rng) * 0.8f, u(rng) * 0.8f, 0.1f * u(rng)};
    w.radius2 = static_cast<float>(radius * radius);
    w.inv_2s2 = 1.0f / (2 * 0.25f * 0.25f);
    w.inv_2n2 = q % 2 ? 1.0f / (2 * 0.15f * 0.15f) : w.inv_2s2;
    w.normal = {0.1f, -0.2f, std::sqrt(1.0f - 0.05f)};
    const NearPointResult got = WeighNearPoints(grid, radius, w);
    const Reference want = Brute(points, w);
    // Points exactly on the sphere may fall either way in float: none here (random floats).
    ASSERT_EQ(got.count, want.count) << "query " << q;
    const double tol = 1e-5 * want.w + 1e-12;
    EXPECT_NEAR(got.acc.weight(), want.w, tol);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(got.acc.WeightedSum()[k], want.s[k], tol * radius);
  }
}

TEST(NearPointSums, NoPointsNearGivesZeroWeight) {
  const std::vector<Point3f> points = {{10, 10, 10}, {10.5f, 10, 10}};
  const PointRowGrid grid(points, 0.5);
  NearPointWeights w;
  w.origin = {0, 0, 0};
  w.radius2 = 1;
  w.inv_2s2 = w.inv_2n2 = 0.5f;
  const NearPointResult got = WeighNearPoints(grid, 1.0, w);
  EXPECT_EQ(got.count, 0);
  EXPECT_EQ(got.acc.weight(), 0.0);
}

TEST(NearPointSums, EveryPointOfALongRunCountsOnce) {
  // A row of 11 points in one row of cells: runs longer than one SIMD step, with a tail.
  std::vector<Point3f> points;
  for (int i = 0; i <= 10; ++i) points.push_back({0.1f * i, 0, 0});
  const PointRowGrid grid(points, 0.5);
  NearPointWeights w;
  w.origin = {0.5f, 0, 0};
  w.radius2 = 100;
  w.inv_2s2 = w.inv_2n2 = 0;  // weight 1 each
  const NearPointResult got = WeighNearPoints(grid, 10.0, w);
  EXPECT_EQ(got.count, 11);
  EXPECT_FLOAT_EQ(static_cast<float>(got.acc.weight()), 11.0f);
  EXPECT_NEAR(got.acc.WeightedSum()[0], 0.0, 1e-5);
}

// The axes (t1, t2, n) of a frame around the unit normal n: t1, t2 an orthonormal tangent basis.
std::array<std::array<double, 3>, 3> FrameAxes(const std::array<double, 3>& n) {
  std::array<double, 3> t1 = {n[2], 0, -n[0]};
  const double l1 = std::sqrt(t1[0] * t1[0] + t1[2] * t1[2]);
  for (double& c : t1) c /= l1;
  const std::array<double, 3> t2 = {n[1] * t1[2] - n[2] * t1[1], n[2] * t1[0] - n[0] * t1[2],
                                    n[0] * t1[1] - n[1] * t1[0]};
  return {t1, t2, n};
}

// A vertex's frame as the fit makes it: the normal (tilt x, tilt y, 1) normalized, x and y
// random in [-1, 1], every axis of length 1 / voxel.
FrameWeights RandomFrame(std::mt19937& rng, double voxel, double tilt) {
  std::uniform_real_distribution<double> g(-1, 1);
  std::array<double, 3> n = {tilt * g(rng), tilt * g(rng), 1};
  const double ln = std::sqrt(n[0] * n[0] + n[1] * n[1] + 1);
  for (double& c : n) c /= ln;
  const auto axes = FrameAxes(n);
  FrameWeights w;
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) w.axes[i][k] = static_cast<float>(axes[i][k] / voxel);
  return w;
}

TEST(NearPointSums, FrameSumsMatchTheDoubleSumsPointByPoint) {
  // A curved noisy sheet in model units (voxel 0.1), queried in tilted frames whose axes have
  // length 1 / voxel: every moment of height_quadric.h against the same sums in double.
  const double voxel = 0.1;
  std::mt19937 rng(9);
  std::uniform_real_distribution<float> u(-1, 1), noise(-0.005f, 0.005f);
  std::vector<Point3f> points(20000);
  for (Point3f& p : points) {
    const float x = u(rng), y = u(rng);
    p = {x, y, 0.3f * x * x - 0.2f * x * y + noise(rng)};
  }
  const double radius = 2 * voxel;
  const PointRowGrid grid(points, radius / 2);
  const auto axes = FrameAxes({0.1, -0.2, std::sqrt(1 - 0.05)});
  for (int q = 0; q < 100; ++q) {
    FrameWeights w;
    const float x = 0.7f * u(rng), y = 0.7f * u(rng);
    w.origin = {x, y, 0.3f * x * x - 0.2f * x * y + 0.1f * u(rng)};
    for (int i = 0; i < 3; ++i)
      for (int k = 0; k < 3; ++k) w.axes[i][k] = static_cast<float>(axes[i][k] / voxel);
    w.radius2 = 4;
    w.inv_2s2 = 0.5f;
    w.inv_2n2 = q % 2 ? 1.0f / (2 * 0.6f * 0.6f) : 0.5f;
    const HeightFieldSums got = WeighNearPointsInFrame(grid, radius, w);
    HeightFieldSums want;
    for (const Point3f& p : points) {
      const double d[3] = {double(p[0]) - w.origin[0], double(p[1]) - w.origin[1],
                           double(p[2]) - w.origin[2]};
      double c[3];
      for (int i = 0; i < 3; ++i)
        c[i] = (d[0] * axes[i][0] + d[1] * axes[i][1] + d[2] * axes[i][2]) / voxel;
      if (c[0] * c[0] + c[1] * c[1] + c[2] * c[2] > w.radius2) continue;
      const double wt =
          std::exp(-(c[0] * c[0] + c[1] * c[1]) * w.inv_2s2 - c[2] * c[2] * w.inv_2n2);
      ++want.count;
      for (int i = 0; i <= 4; ++i)
        for (int j = 0; i + j <= 4; ++j)
          want.uv[HeightFieldSums::Index(i, j)] += wt * std::pow(c[0], i) * std::pow(c[1], j);
      for (int i = 0; i <= 2; ++i)
        for (int j = 0; i + j <= 2; ++j)
          want.huv[HeightFieldSums::Index(i, j)] +=
              wt * c[2] * std::pow(c[0], i) * std::pow(c[1], j);
      want.hh += wt * c[2] * c[2];
    }
    // Points within float rounding of the ball's surface may fall either way: allow one.
    ASSERT_NEAR(got.count, want.count, 1) << "query " << q;
    if (got.count != want.count) continue;
    // Moments up to degree 4 of coordinates up to 2: scale the tolerance by 16 * weight.
    const double tol = 1e-4 * (want.uv[0] + 1e-9) * 16;
    for (int k = 0; k < 15; ++k) EXPECT_NEAR(got.uv[k], want.uv[k], tol) << q << " uv " << k;
    for (int k = 0; k < 6; ++k) EXPECT_NEAR(got.huv[k], want.huv[k], tol) << q << " huv " << k;
    EXPECT_NEAR(got.hh, want.hh, tol) << q;
  }
}

// WeighNearPointsInFrame's loop over every step of every run, the steps with no point within the
// radius included (counted in `empty_steps`): the sums a fit's target was computed from before
// those steps were skipped.
HeightFieldSums EveryStep(const PointRowGrid& grid, double radius, const FrameWeights& w,
                          int& empty_steps) {
  const auto splat = [](float f) { return V4f{f, f, f, f}; };
  const auto load = [](const float* p) {
    V4f v;
    std::memcpy(&v, p, sizeof(v));
    return v;
  };
  const V4f ox = splat(w.origin[0]), oy = splat(w.origin[1]), oz = splat(w.origin[2]);
  V4f ax[3][3];
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) ax[i][k] = splat(w.axes[i][k]);
  const V4f r2 = splat(w.radius2), a = splat(w.inv_2s2), b = splat(w.inv_2n2);
  const V4i lane = {0, 1, 2, 3};
  V4f m[15], hm[6], shh = splat(0);
  for (V4f& x : m) x = splat(0);
  for (V4f& x : hm) x = splat(0);
  V4i count = {0, 0, 0, 0};
  const Vec3d centre{w.origin[0], w.origin[1], w.origin[2]};
  grid.ForEachRun(centre, radius, [&](uint32_t begin, uint32_t end) {
    for (uint32_t i = begin; i < end; i += 4) {
      const V4f dx = load(grid.xs() + i) - ox, dy = load(grid.ys() + i) - oy,
                dz = load(grid.zs() + i) - oz;
      const V4f u = dx * ax[0][0] + dy * ax[0][1] + dz * ax[0][2];
      const V4f v = dx * ax[1][0] + dy * ax[1][1] + dz * ax[1][2];
      const V4f h = dx * ax[2][0] + dy * ax[2][1] + dz * ax[2][2];
      const V4f uu = u * u, uv = u * v, vv = v * v, h2 = h * h;
      const V4f t2 = uu + vv;
      const V4i inside = (t2 + h2 <= r2) & (lane < static_cast<int32_t>(end - i));
      empty_steps += (inside[0] | inside[1] | inside[2] | inside[3]) == 0;
      const V4f wt = std::bit_cast<V4f>(std::bit_cast<V4i>(ExpNeg4(t2 * a + h2 * b)) & inside);
      count -= inside;
      const V4f wu = wt * u, wv = wt * v, wuu = wt * uu, wvv = wt * vv, wuv = wt * uv,
                wh = wt * h;
      const V4f terms[15] = {wt,       wu,       wv,       wuu,      wuv,
                             wvv,      wuu * u,  wuu * v,  wvv * u,  wvv * v,
                             wuu * uu, wuu * uv, wuu * vv, wvv * uv, wvv * vv};
      for (int k = 0; k < 15; ++k) m[k] += terms[k];
      const V4f hterms[6] = {wh, wh * u, wh * v, wh * uu, wh * uv, wh * vv};
      for (int k = 0; k < 6; ++k) hm[k] += hterms[k];
      shh += wh * h;
    }
  });
  const auto sum = [](V4f x) { return (x[0] + x[1]) + (x[2] + x[3]); };
  HeightFieldSums out;
  out.count = count[0] + count[1] + count[2] + count[3];
  for (int k = 0; k < 15; ++k) out.uv[k] = sum(m[k]);
  for (int k = 0; k < 6; ++k) out.huv[k] = sum(hm[k]);
  out.hh = sum(shh);
  return out;
}

TEST(NearPointSums, FrameSumsSkipOnlyStepsThatAddNothing) {
  // A sheet of 1.5 points per voxel face, queried at and off it in a random frame: the box
  // of cells around the ball holds many steps of four points none of which is within the
  // radius. Leaving them out must give the very same bits as weighing them (the fitted mesh
  // is byte-identical), not only the same sums within rounding.
  const double voxel = 0.1;
  std::mt19937 rng(21);
  std::uniform_real_distribution<float> u(-1, 1), noise(-0.01f, 0.01f);
  std::vector<Point3f> points(60000);
  for (Point3f& p : points) {
    const float x = u(rng), y = u(rng);
    p = {x, y, 0.2f * x * y + noise(rng)};
  }
  for (const double radius_voxels : {2.0, 4.0}) {
    const double radius = radius_voxels * voxel;
    const PointRowGrid grid(points, voxel);
    int skipped = 0;
    for (int q = 0; q < 300; ++q) {
      // Up to the sheet's edge (runs ending at the last stored point included).
      const float x = 1.05f * u(rng), y = 1.05f * u(rng);
      FrameWeights w = RandomFrame(rng, voxel, 0.3);
      w.origin = {x, y, 0.2f * x * y + 0.15f * u(rng)};
      w.radius2 = static_cast<float>(radius_voxels * radius_voxels);
      w.inv_2s2 = q % 3 ? 0.5f : 0.125f;
      w.inv_2n2 = q % 2 ? 1.0f / (2 * 0.6f * 0.6f) : 0.5f;
      const HeightFieldSums got = WeighNearPointsInFrame(grid, radius, w);
      int empty_steps = 0;
      const HeightFieldSums want = EveryStep(grid, radius, w, empty_steps);
      ASSERT_EQ(got.count, want.count) << "query " << q;
      for (int k = 0; k < 15; ++k) EXPECT_EQ(got.uv[k], want.uv[k]) << q << " uv " << k;
      for (int k = 0; k < 6; ++k) EXPECT_EQ(got.huv[k], want.huv[k]) << q << " huv " << k;
      EXPECT_EQ(got.hh, want.hh) << q;
      skipped += empty_steps > 0;
    }
    // The case under test occurs: most queries have steps wholly outside the ball.
    EXPECT_GT(skipped, 250) << radius_voxels;
  }
}

TEST(NearPointSums, TheWideInstructionsGiveTheBaselineBits) {
  // The sums of both weighings, on both kinds of grid (points, and cell means weighted by
  // their counts), at the fit's two radii: the widest instructions this processor has
  // against the baseline's, bit for bit (the fitted mesh must be the same on every machine).
  if (!HasWideSumsInstructions()) GTEST_SKIP() << "this processor has no wider instructions";
  const double voxel = 0.1;
  std::mt19937 rng(33);
  std::uniform_real_distribution<float> u(-1, 1), noise(-0.02f, 0.02f), count(1, 9);
  std::vector<Point3f> points(40000);
  std::vector<float> counts(points.size());
  for (size_t i = 0; i < points.size(); ++i) {
    const float x = u(rng), y = u(rng);
    points[i] = {x, y, 0.3f * x * x - 0.2f * x * y + noise(rng)};
    counts[i] = std::floor(count(rng));
  }
  int compared = 0;
  for (const bool weighted : {false, true}) {
    const PointRowGrid grid(points, voxel, 1, PointRowGrid::Limits(),
                            weighted ? absl::Span<const float>(counts) : absl::Span<const float>());
    for (const double radius_voxels : {2.0, 4.0}) {
      const double radius = radius_voxels * voxel;
      for (int q = 0; q < 200; ++q) {
        const float x = 1.05f * u(rng), y = 1.05f * u(rng);
        const Point3f origin = {x, y, 0.3f * x * x - 0.2f * x * y + 0.1f * u(rng)};
        FrameWeights f = RandomFrame(rng, voxel, 0.4);
        f.origin = origin;
        f.radius2 = static_cast<float>(radius_voxels * radius_voxels);
        f.inv_2s2 = q % 3 ? 0.5f : 0.125f;
        f.inv_2n2 = q % 2 ? 1.0f / (2 * 0.6f * 0.6f) : f.inv_2s2;
        const HeightFieldSums a = WeighNearPointsInFrame(grid, radius, f, SumsInstructions::kBest);
        const HeightFieldSums b =
            WeighNearPointsInFrame(grid, radius, f, SumsInstructions::kBaseline);
        ASSERT_EQ(a.count, b.count) << q;
        for (int k = 0; k < 15; ++k) EXPECT_EQ(a.uv[k], b.uv[k]) << q << " uv " << k;
        for (int k = 0; k < 6; ++k) EXPECT_EQ(a.huv[k], b.huv[k]) << q << " huv " << k;
        EXPECT_EQ(a.hh, b.hh) << q;

        NearPointWeights w;
        w.origin = origin;
        w.radius2 = static_cast<float>(radius * radius);
        w.inv_2s2 = static_cast<float>(f.inv_2s2 / (voxel * voxel));
        w.inv_2n2 = static_cast<float>(f.inv_2n2 / (voxel * voxel));
        for (int k = 0; k < 3; ++k) w.normal[k] = f.axes[2][k] * static_cast<float>(voxel);
        const NearPointResult c = WeighNearPoints(grid, radius, w, SumsInstructions::kBest);
        const NearPointResult d = WeighNearPoints(grid, radius, w, SumsInstructions::kBaseline);
        ASSERT_EQ(c.count, d.count) << q;
        EXPECT_EQ(c.acc.weight(), d.acc.weight()) << q;
        for (int k = 0; k < 3; ++k) EXPECT_EQ(c.acc.WeightedSum()[k], d.acc.WeightedSum()[k]) << q;
        const auto pc = c.acc.Fit(), pd = d.acc.Fit();
        ASSERT_EQ(pc.has_value(), pd.has_value()) << q;
        if (pc) {
          for (int k = 0; k < 3; ++k) EXPECT_EQ(pc->centroid[k], pd->centroid[k]) << q;
          for (int k = 0; k < 3; ++k) EXPECT_EQ(pc->normal[k], pd->normal[k]) << q;
        }
        compared += a.count > 0 && c.count > 0;
      }
    }
  }
  // Most queries weigh points (a few lie beyond the sheet's edge).
  EXPECT_GT(compared, 700);
}

TEST(NearPointSums, FrameSumsKeepTheirBitsAtAnyScale) {
  // The same sheet in model units 2^-20 times smaller (a voxel of 1e-7: a part of a few
  // millimetres given in metres): offsets and frame axes scale by powers of 2, so every frame
  // coordinate, and so every sum, has the same bits. Queried at the last points the grid
  // stores, whose runs end at the arrays' end: the lanes read past it must not overflow in a
  // frame whose axes have length 1e7.
  const double voxel = 0.1, scale = std::ldexp(1.0, -20);
  std::mt19937 rng(35);
  std::uniform_real_distribution<float> u(-1, 1), noise(-0.02f, 0.02f);
  std::vector<Point3f> points(20000), tiny(points.size());
  for (size_t i = 0; i < points.size(); ++i) {
    const float x = u(rng), y = u(rng);
    points[i] = {x, y, 0.3f * x * x - 0.2f * x * y + noise(rng)};
    for (int k = 0; k < 3; ++k) tiny[i][k] = static_cast<float>(points[i][k] * scale);
  }
  const PointRowGrid grid(points, 2 * voxel), tiny_grid(tiny, 2 * voxel * scale);
  ASSERT_EQ(grid.num_points(), tiny_grid.num_points());
  int weighed = 0;
  for (size_t back = 1; back <= 40; ++back) {
    const size_t last = grid.num_points() - back;
    FrameWeights f = RandomFrame(rng, voxel, 0.3);
    f.origin = {grid.xs()[last], grid.ys()[last], grid.zs()[last]};
    f.radius2 = 4;
    f.inv_2s2 = 0.5f;
    f.inv_2n2 = 1.0f / (2 * 0.6f * 0.6f);
    FrameWeights g = f;
    for (int k = 0; k < 3; ++k) g.origin[k] = static_cast<float>(f.origin[k] * scale);
    for (auto& axis : g.axes)
      for (float& c : axis) c = static_cast<float>(c / scale);
    for (const SumsInstructions instructions :
         {SumsInstructions::kBest, SumsInstructions::kBaseline}) {
      const HeightFieldSums a = WeighNearPointsInFrame(grid, 2 * voxel, f, instructions);
      const HeightFieldSums b = WeighNearPointsInFrame(tiny_grid, 2 * voxel * scale, g, instructions);
      ASSERT_EQ(a.count, b.count) << back;
      for (int k = 0; k < 15; ++k) EXPECT_EQ(a.uv[k], b.uv[k]) << back << " uv " << k;
      for (int k = 0; k < 6; ++k) EXPECT_EQ(a.huv[k], b.huv[k]) << back << " huv " << k;
      EXPECT_EQ(a.hh, b.hh) << back;
      weighed += a.count > 0;
    }
  }
  EXPECT_GT(weighed, 40);
}

}  // namespace
}  // namespace membrane
