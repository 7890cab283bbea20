#include "core/mesh/fast_exp.h"

#include <algorithm>
#include <cmath>

#include "gtest/gtest.h"

namespace membrane {
namespace {

TEST(FastExp, MatchesTheLibraryWithin3e7Relative) {
  double worst = 0;
  for (float x = 0; x <= 87; x += 4 * 0.000731f) {
    const V4f got = ExpNeg4(V4f{x, x + 0.000731f, x + 2 * 0.000731f, x + 3 * 0.000731f});
    for (int l = 0; l < 4; ++l) {
      const double xl = static_cast<double>(x + l * 0.000731f);
      if (xl > 87) continue;
      const double exact = std::exp(-xl);
      worst = std::max(worst, std::fabs(got[l] - exact) / exact);
    }
  }
  EXPECT_LT(worst, 3e-7);
}

TEST(FastExp, IsExactAtZeroAndClampsOutsideItsRange) {
  const V4f got = ExpNeg4(V4f{0, -3, 1e30f, 87});
  EXPECT_EQ(got[0], 1.0f);
  EXPECT_EQ(got[1], 1.0f);
  EXPECT_GT(got[2], 0.0f);
  EXPECT_EQ(got[2], got[3]);
  EXPECT_LE(got[2], std::exp(-87.0) * (1 + 1e-6));
}

}  // namespace
}  // namespace membrane
