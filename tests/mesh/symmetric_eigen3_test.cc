// The symmetric 3x3 eigen solve (core/geometry/symmetric_eigen3.h): eigenvalues in order for
// diagonal and rotated matrices, the least eigenvector to rounding, and no eigenvector where
// the eigenspace is not a line.
#include "core/geometry/symmetric_eigen3.h"

#include <cmath>

#include "gtest/gtest.h"

namespace membrane {
namespace {

// R diag(l) R^T for the orthonormal columns of `r`.
SymmetricMatrix3 Rotated(const std::array<Vec3d, 3>& r, const Vec3d& l) {
  auto entry = [&](int i, int j) {
    double s = 0;
    for (int k = 0; k < 3; ++k) s += r[k][i] * l[k] * r[k][j];
    return s;
  };
  return {entry(0, 0), entry(0, 1), entry(0, 2), entry(1, 1), entry(1, 2), entry(2, 2)};
}

void ExpectEigenvalues(const Eigenvalues3& values, double smallest, double middle,
                       double largest) {
  EXPECT_NEAR(values.smallest, smallest, 1e-12);
  EXPECT_NEAR(values.middle, middle, 1e-12);
  EXPECT_NEAR(values.largest, largest, 1e-12);
}

TEST(SymmetricEigen3, DiagonalMatrix) {
  const SymmetricMatrix3 m = {3, 0, 0, 1, 0, 2};
  const Eigenvalues3 values = SymmetricEigenvalues(m);
  ExpectEigenvalues(values, 1, 2, 3);
  const auto v = EigenvectorOf(m, values.smallest);
  ASSERT_TRUE(v);
  EXPECT_NEAR(std::abs((*v)[1]), 1, 1e-12);
  EXPECT_NEAR(Norm(*v), 1, 1e-15);
}

TEST(SymmetricEigen3, RotatedMatrixGivesItsAxes) {
  // An orthonormal frame: (1, 2, 2) / 3 and two vectors across it.
  const Vec3d n = {1.0 / 3, 2.0 / 3, 2.0 / 3};
  const Vec3d t1 = Normalized(Cross(n, Vec3d{1, 0, 0}));
  const Vec3d t2 = Cross(n, t1);
  const SymmetricMatrix3 m = Rotated({n, t1, t2}, {0.01, 1, 4});
  const Eigenvalues3 values = SymmetricEigenvalues(m);
  ExpectEigenvalues(values, 0.01, 1, 4);
  const auto least = EigenvectorOf(m, values.smallest);
  ASSERT_TRUE(least);
  EXPECT_NEAR(std::abs(Dot(*least, n)), 1, 1e-12);
  EXPECT_NEAR(Norm(*least), 1, 1e-15);
  const auto most = EigenvectorOf(m, values.largest);
  ASSERT_TRUE(most);
  EXPECT_NEAR(std::abs(Dot(*most, t2)), 1, 1e-12);
}

TEST(SymmetricEigen3, MultipleOfTheIdentityHasNoEigenvectorLine) {
  const SymmetricMatrix3 m = {2, 0, 0, 2, 0, 2};
  const Eigenvalues3 values = SymmetricEigenvalues(m);
  EXPECT_EQ(values.smallest, 2);
  EXPECT_EQ(values.middle, 2);
  EXPECT_EQ(values.largest, 2);
  EXPECT_FALSE(EigenvectorOf(m, values.smallest));
}

TEST(SymmetricEigen3, NotFiniteGivesNoEigenvector) {
  const SymmetricMatrix3 m = {1, 0, 0, std::nan(""), 0, 2};
  EXPECT_FALSE(EigenvectorOf(m, SymmetricEigenvalues(m).smallest));
}

}  // namespace
}  // namespace membrane
