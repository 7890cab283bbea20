#include "core/mesh/fast_exp.h"

#include <cmath>

#include "gtest/gtest.h"

namespace membrane {
namespace {

TEST(FastExp, MatchesTheLibraryWithin1e15Relative) {
  double worst = 0;
  for (double x = 0; x <= 700; x += 0.000731) {
    const double exact = std::exp(-x);
    worst = std::max(worst, std::fabs(ExpNeg(x) - exact) / exact);
  }
  EXPECT_LT(worst, 1e-15);
}

TEST(FastExp, IsExactAtZeroAndClampsOutsideItsRange) {
  EXPECT_EQ(ExpNeg(0), 1.0);
  EXPECT_EQ(ExpNeg(-3), 1.0);
  EXPECT_GT(ExpNeg(1e9), 0.0);
  EXPECT_LE(ExpNeg(1e9), std::exp(-700) * (1 + 1e-14));
}

TEST(FastExp, FloatVersionMatchesTheLibraryWithin3e7Relative) {
  double worst = 0;
  for (float x = 0; x <= 87; x += 0.000731f) {
    const double exact = std::exp(-static_cast<double>(x));
    worst = std::max(worst, std::fabs(ExpNegF(x) - exact) / exact);
  }
  EXPECT_LT(worst, 3e-7);
}

TEST(FastExp, FloatVersionIsExactAtZeroAndClampsOutsideItsRange) {
  EXPECT_EQ(ExpNegF(0), 1.0f);
  EXPECT_EQ(ExpNegF(-3), 1.0f);
  EXPECT_GT(ExpNegF(1e30f), 0.0f);
  EXPECT_LE(ExpNegF(1e30f), std::exp(-87.0) * (1 + 1e-6));
}

}  // namespace
}  // namespace membrane
