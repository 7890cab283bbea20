#include "core/mesh/plane_fit.h"

#include <algorithm>

#include "core/geometry/symmetric_eigen3.h"

namespace membrane {

std::optional<PlaneFitAccumulator::Plane> PlaneFitAccumulator::Fit() const {
  if (sw_ <= 0) return std::nullopt;
  const Vec3d c = (1.0 / sw_) * s_;
  const SymmetricMatrix3 covariance = {
      s2_[0] / sw_ - c[0] * c[0], s2_[1] / sw_ - c[0] * c[1], s2_[2] / sw_ - c[0] * c[2],
      s2_[3] / sw_ - c[1] * c[1], s2_[4] / sw_ - c[1] * c[2], s2_[5] / sw_ - c[2] * c[2]};
  const Eigenvalues3 spread = SymmetricEigenvalues(covariance);
  // Also where the covariance is isotropic (all three equal).
  if (spread.middle - spread.smallest < 1e-3 * std::max(spread.largest, 1e-300))
    return std::nullopt;
  const std::optional<Vec3d> normal = EigenvectorOf(covariance, spread.smallest);
  if (!normal) return std::nullopt;
  return Plane{c, *normal};
}

}  // namespace membrane
