// Eigenvalues and eigenvectors of a symmetric 3x3 matrix in closed form: the covariance of a
// few points, whose least eigenpair gives their best plane's normal and their spread across it
// (a vertex's fitted plane, the thin-part test's spread, a plugged hole's wall, a noise box).
#ifndef MEMBRANE_CORE_GEOMETRY_SYMMETRIC_EIGEN3_H_
#define MEMBRANE_CORE_GEOMETRY_SYMMETRIC_EIGEN3_H_

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <optional>

#include "core/geometry/vec3.h"

namespace membrane {

// A symmetric 3x3 matrix as its upper triangle: xx, xy, xz, yy, yz, zz.
using SymmetricMatrix3 = std::array<double, 6>;

struct Eigenvalues3 {
  double smallest = 0;
  double middle = 0;
  double largest = 0;
};

// The eigenvalues of `m`, smallest to largest, by the trigonometric solution of its
// characteristic cubic; all three the mean of the diagonal when `m` is a multiple of the
// identity. cos(phi + 2 pi / 3) comes from the cos and sin of phi: one library call fewer, in
// a surface fit's hottest few lines after the point weights.
inline Eigenvalues3 SymmetricEigenvalues(const SymmetricMatrix3& m) {
  const auto [a, b, c, d, e, f] = m;
  const double q = (a + d + f) / 3;
  const double off = b * b + c * c + e * e;
  const double p2 = (a - q) * (a - q) + (d - q) * (d - q) + (f - q) * (f - q) + 2 * off;
  if (p2 <= 0) return {q, q, q};
  const double p = std::sqrt(p2 / 6);
  const double ma = (a - q) / p, mb = b / p, mc = c / p, md = (d - q) / p, me = e / p,
               mf = (f - q) / p;
  const double det = ma * (md * mf - me * me) - mb * (mb * mf - me * mc) + mc * (mb * me - md * mc);
  const double phi = std::acos(std::clamp(det / 2, -1.0, 1.0)) / 3;
  // phi is in [0, pi / 3], so the sine is the positive root.
  const double cos_phi = std::cos(phi);
  const double sin_phi = std::sqrt(std::max(0.0, 1 - cos_phi * cos_phi));
  Eigenvalues3 values;
  values.largest = q + 2 * p * cos_phi;
  values.smallest = q + 2 * p * (-0.5 * cos_phi - 0.5 * std::numbers::sqrt3 * sin_phi);
  values.middle = 3 * q - values.largest - values.smallest;
  return values;
}

// A unit eigenvector of `m` for its eigenvalue `lambda` (one of SymmetricEigenvalues(m)), its
// sign arbitrary: the largest cross product of two rows of m - lambda I, which spans their
// null space (any two independent rows give it; the largest is the best conditioned). nullopt
// when every such product is zero or not finite: lambda's eigenspace is not a line that those
// rows pin down (m a multiple of the identity, lambda a double eigenvalue).
inline std::optional<Vec3d> EigenvectorOf(const SymmetricMatrix3& m, double lambda) {
  const Vec3d r0{m[0] - lambda, m[1], m[2]}, r1{m[1], m[3] - lambda, m[4]},
      r2{m[2], m[4], m[5] - lambda};
  Vec3d best = Cross(r0, r1);
  for (const Vec3d& v : {Cross(r0, r2), Cross(r1, r2)})
    if (SquaredNorm(v) > SquaredNorm(best)) best = v;
  const double n = Norm(best);
  if (!(n > 0)) return std::nullopt;
  return (1.0 / n) * best;
}

}  // namespace membrane

#endif  // MEMBRANE_CORE_GEOMETRY_SYMMETRIC_EIGEN3_H_
