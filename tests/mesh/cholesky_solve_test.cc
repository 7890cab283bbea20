// The small dense Cholesky solve (core/geometry/cholesky_solve.h): it solves known systems to
// rounding, leaves the factor in the lower triangle and reads nothing above it, recovers a
// height quadric from its normal equations, and reports a singular, indefinite, nearly
// dependent or non-finite system as a failure rather than a NaN solution.
#include "core/geometry/cholesky_solve.h"

#include <array>
#include <cmath>
#include <limits>

#include "gtest/gtest.h"

namespace membrane {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

TEST(CholeskySolve, SolvesAKnownSystemAndLeavesItsFactor) {
  // L = [2 0 0; 6 1 0; -8 5 3], x = (1, 2, 3).
  SquareMatrix<3> a = {{{4, 12, -16}, {12, 37, -43}, {-16, -43, 98}}};
  std::array<double, 3> b = {-20, -43, 192};
  ASSERT_TRUE(CholeskySolve(a, b, 1e-7));
  EXPECT_NEAR(b[0], 1, 1e-12);
  EXPECT_NEAR(b[1], 2, 1e-12);
  EXPECT_NEAR(b[2], 3, 1e-12);
  EXPECT_DOUBLE_EQ(a[0][0], 2);
  EXPECT_DOUBLE_EQ(a[1][0], 6);
  EXPECT_DOUBLE_EQ(a[1][1], 1);
  EXPECT_DOUBLE_EQ(a[2][0], -8);
  EXPECT_DOUBLE_EQ(a[2][1], 5);
  EXPECT_DOUBLE_EQ(a[2][2], 3);
}

TEST(CholeskySolve, ReadsOnlyTheLowerTriangle) {
  SquareMatrix<3> a = {{{4, kNaN, kNaN}, {12, 37, kNaN}, {-16, -43, 98}}};
  std::array<double, 3> b = {-20, -43, 192};
  ASSERT_TRUE(CholeskySolve(a, b, 1e-7));
  EXPECT_NEAR(b[0], 1, 1e-12);
  EXPECT_NEAR(b[1], 2, 1e-12);
  EXPECT_NEAR(b[2], 3, 1e-12);
}

TEST(CholeskySolve, RecoversAHeightQuadricFromItsNormalEquations) {
  // h = f + d u + e v + a u^2 + b u v + c v^2 sampled on a 7 x 7 grid, basis 1 u v u^2 uv v^2.
  const std::array<double, 6> want = {0.1, 0.2, -0.3, 0.5, -0.25, 0.125};
  SquareMatrix<6> m{};
  std::array<double, 6> r{};
  for (int i = -3; i <= 3; ++i) {
    for (int j = -3; j <= 3; ++j) {
      const double u = 0.4 * i, v = 0.3 * j;
      const std::array<double, 6> t = {1, u, v, u * u, u * v, v * v};
      double h = 0;
      for (int k = 0; k < 6; ++k) h += want[k] * t[k];
      for (int p = 0; p < 6; ++p) {
        for (int q = 0; q < 6; ++q) m[p][q] += t[p] * t[q];
        r[p] += t[p] * h;
      }
    }
  }
  ASSERT_TRUE(CholeskySolve(m, r, 1e-7));
  for (int k = 0; k < 6; ++k) EXPECT_NEAR(r[k], want[k], 1e-12) << k;
}

TEST(CholeskySolve, ReportsASingularSystem) {
  // Rank 1: the second column is twice the first.
  SquareMatrix<2> a = {{{1, 2}, {2, 4}}};
  std::array<double, 2> b = {1, 2};
  EXPECT_FALSE(CholeskySolve(a, b, 1e-7));
  SquareMatrix<2> zero{};
  std::array<double, 2> c = {0, 0};
  EXPECT_FALSE(CholeskySolve(zero, c, 1e-7));
  // Points on a line u = v: the height quadric's columns u and v are equal.
  SquareMatrix<6> m{};
  std::array<double, 6> r{};
  for (int i = -3; i <= 3; ++i) {
    const double u = 0.5 * i, v = u;
    const std::array<double, 6> t = {1, u, v, u * u, u * v, v * v};
    for (int p = 0; p < 6; ++p) {
      for (int q = 0; q < 6; ++q) m[p][q] += t[p] * t[q];
      r[p] += t[p] * u;
    }
  }
  EXPECT_FALSE(CholeskySolve(m, r, 1e-7));
}

TEST(CholeskySolve, ReportsAnIndefiniteSystem) {
  SquareMatrix<2> a = {{{1, 2}, {2, 1}}};
  std::array<double, 2> b = {1, 1};
  EXPECT_FALSE(CholeskySolve(a, b, 1e-7));
  SquareMatrix<2> negative = {{{-1, 0}, {0, -1}}};
  std::array<double, 2> c = {1, 1};
  EXPECT_FALSE(CholeskySolve(negative, c, 0));
}

TEST(CholeskySolve, NearlyDependentColumnsFailBelowTheMinimumPivot) {
  // The second pivot is 1e-9 of its diagonal entry.
  const SquareMatrix<2> a = {{{1, 1}, {1, 1 + 1e-9}}};
  const std::array<double, 2> b = {2, 2 + 1e-9};
  SquareMatrix<2> strict = a;
  std::array<double, 2> x = b;
  EXPECT_FALSE(CholeskySolve(strict, x, 1e-7));
  SquareMatrix<2> loose = a;
  std::array<double, 2> y = b;
  ASSERT_TRUE(CholeskySolve(loose, y, 1e-12));
  EXPECT_NEAR(y[0], 1, 1e-6);
  EXPECT_NEAR(y[1], 1, 1e-6);
}

TEST(CholeskySolve, SmallPivotsFailBelowTheAbsoluteMinimum) {
  // Independent columns, one of them tiny: its pivot, 1e-12, is all of its diagonal entry.
  const SquareMatrix<2> a = {{{1, 0}, {0, 1e-12}}};
  const std::array<double, 2> b = {1, 1e-12};
  SquareMatrix<2> relative = a;
  std::array<double, 2> x = b;
  ASSERT_TRUE(CholeskySolve(relative, x, 1e-7));
  EXPECT_DOUBLE_EQ(x[1], 1);
  SquareMatrix<2> absolute = a;
  std::array<double, 2> y = b;
  EXPECT_FALSE(CholeskySolve(absolute, y, 0, 1e-9));
}

TEST(CholeskySolve, ReportsNonFiniteEntries) {
  SquareMatrix<2> a = {{{1, 0}, {kNaN, 1}}};
  std::array<double, 2> b = {1, 1};
  EXPECT_FALSE(CholeskySolve(a, b, 1e-7));
  SquareMatrix<2> c = {{{1, 0}, {0, std::numeric_limits<double>::infinity()}}};
  std::array<double, 2> d = {1, 1};
  EXPECT_FALSE(CholeskySolve(c, d, 1e-7));
}

}  // namespace
}  // namespace membrane
