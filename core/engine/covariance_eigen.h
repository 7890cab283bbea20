// The least eigenpair of a 3x3 covariance: the spread and the direction across the best plane
// of a few points (the thin-part test's spread, a plugged hole's wall normal, the points'
// noise across their surface).
#ifndef MEMBRANE_CORE_ENGINE_COVARIANCE_EIGEN_H_
#define MEMBRANE_CORE_ENGINE_COVARIANCE_EIGEN_H_

#include <array>

namespace membrane {

// A symmetric 3x3 matrix as its upper triangle: xx, xy, xz, yy, yz, zz.
using SymmetricMatrix3 = std::array<double, 6>;

// The smallest eigenvalue of `m` (the trigonometric solution of its characteristic cubic).
double SmallestEigenvalue(const SymmetricMatrix3& m);

// A unit eigenvector of `m` for its smallest eigenvalue, its sign arbitrary, into `v`. False
// (and `v` untouched) when that eigenvalue's eigenspace is not a line the rows of m - lambda I
// pin down (m a multiple of the identity, or the two smallest eigenvalues equal).
bool SmallestEigenvector(const SymmetricMatrix3& m, std::array<double, 3>& v);

}  // namespace membrane

#endif  // MEMBRANE_CORE_ENGINE_COVARIANCE_EIGEN_H_
