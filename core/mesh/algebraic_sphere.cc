#include "core/mesh/algebraic_sphere.h"

#include <cmath>

namespace membrane {
namespace {

// Below this |u4| (per unit length, with unit normals: the inverse of twice the radius) the
// sphere is taken as its plane: radii over 10^9 units cannot be told from one, and the centre
// would lose the distance to cancellation.
constexpr double kFlat = 5e-10;

}  // namespace

std::optional<AlgebraicSphere> AlgebraicSphere::Fit(absl::Span<const Vec3d> positions,
                                                    absl::Span<const Vec3d> normals) {
  const size_t n = positions.size();
  if (n < 2 || normals.size() != n) return std::nullopt;
  AlgebraicSphere s;
  for (const Vec3d& p : positions) s.origin_ = s.origin_ + p;
  s.origin_ = (1.0 / static_cast<double>(n)) * s.origin_;
  // Sums relative to the centroid: sum p is 0 up to rounding, kept for exactness.
  Vec3d sp{0, 0, 0}, sn{0, 0, 0};
  double spn = 0, spp = 0;
  for (size_t i = 0; i < n; ++i) {
    const Vec3d p = positions[i] - s.origin_;
    sp = sp + p;
    sn = sn + normals[i];
    spn += Dot(p, normals[i]);
    spp += Dot(p, p);
  }
  const double inv_n = 1.0 / static_cast<double>(n);
  const double spread = spp - inv_n * Dot(sp, sp);
  if (!(spread > 0)) return std::nullopt;
  s.quadratic_ = 0.5 * (spn - inv_n * Dot(sp, sn)) / spread;
  s.linear_ = inv_n * (sn - 2.0 * s.quadratic_ * sp);
  s.constant_ = -inv_n * (Dot(s.linear_, sp) + s.quadratic_ * spp);
  if (!std::isfinite(s.quadratic_) || !std::isfinite(s.constant_) ||
      !std::isfinite(s.linear_[0] + s.linear_[1] + s.linear_[2]))
    return std::nullopt;
  if (std::abs(s.quadratic_) < kFlat) {
    if (!(Norm(s.linear_) > 0)) return std::nullopt;
    s.quadratic_ = 0;
    return s;
  }
  s.centre_ = (-0.5 / s.quadratic_) * s.linear_;
  const double r2 = Dot(s.centre_, s.centre_) - s.constant_ / s.quadratic_;
  if (!(r2 > 0) || !std::isfinite(r2)) return std::nullopt;
  s.radius_ = (s.quadratic_ > 0 ? 1.0 : -1.0) * std::sqrt(r2);
  return s;
}

double AlgebraicSphere::Distance(const Vec3d& p) const {
  const Vec3d q = p - origin_;
  if (quadratic_ == 0) return std::abs(constant_ + Dot(linear_, q)) / Norm(linear_);
  return std::abs(Norm(q - centre_) - std::abs(radius_));
}

}  // namespace membrane
