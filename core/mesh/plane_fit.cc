#include "core/mesh/plane_fit.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace membrane {

std::optional<PlaneFitAccumulator::Plane> PlaneFitAccumulator::Fit() const {
  if (sw_ <= 0) return std::nullopt;
  const Vec3d c = (1.0 / sw_) * s_;
  // Covariance, symmetric: a b c / b d e / c e f.
  const double a = s2_[0] / sw_ - c[0] * c[0], b = s2_[1] / sw_ - c[0] * c[1],
               cc = s2_[2] / sw_ - c[0] * c[2], d = s2_[3] / sw_ - c[1] * c[1],
               e = s2_[4] / sw_ - c[1] * c[2], f = s2_[5] / sw_ - c[2] * c[2];
  // Eigenvalues in closed form (trigonometric solution of the characteristic cubic).
  const double q = (a + d + f) / 3;
  const double p1 = b * b + cc * cc + e * e;
  const double p2 = (a - q) * (a - q) + (d - q) * (d - q) + (f - q) * (f - q) + 2 * p1;
  if (p2 <= 0) return std::nullopt;  // isotropic
  const double p = std::sqrt(p2 / 6);
  const double ba = (a - q) / p, bb = b / p, bc = cc / p, bd = (d - q) / p, be = e / p,
               bf = (f - q) / p;
  const double det = ba * (bd * bf - be * be) - bb * (bb * bf - be * bc) + bc * (bb * be - bd * bc);
  const double phi = std::acos(std::clamp(det / 2, -1.0, 1.0)) / 3;
  // cos(phi + 2 pi / 3) from cos and sin of phi (in [0, pi / 3], so the sine is the positive
  // root): one library call fewer, in a fit's hottest few lines after the point weights.
  const double cos_phi = std::cos(phi);
  const double sin_phi = std::sqrt(std::max(0.0, 1 - cos_phi * cos_phi));
  const double largest = q + 2 * p * cos_phi;
  const double smallest = q + 2 * p * (-0.5 * cos_phi - 0.5 * std::numbers::sqrt3 * sin_phi);
  const double middle = 3 * q - largest - smallest;
  if (middle - smallest < 1e-3 * std::max(largest, 1e-300)) return std::nullopt;
  // Eigenvector of `smallest`: the largest cross product of two rows of (C - smallest I).
  const Vec3d r0{a - smallest, b, cc}, r1{b, d - smallest, e}, r2{cc, e, f - smallest};
  Vec3d best = Cross(r0, r1);
  for (const Vec3d& v : {Cross(r0, r2), Cross(r1, r2)})
    if (SquaredNorm(v) > SquaredNorm(best)) best = v;
  const double n = Norm(best);
  if (!(n > 0)) return std::nullopt;
  return Plane{c, (1.0 / n) * best};
}

}  // namespace membrane
