// A thin-plate spline height field over a plane: the smoothest surface (least bending energy)
// through scattered heights, the classic scattered-data interpolant (Duchon 1977), for the hole
// caps (hole_caps.h).
#ifndef MEMBRANE_CORE_MESH_THIN_PLATE_SPLINE_H_
#define MEMBRANE_CORE_MESH_THIN_PLATE_SPLINE_H_

#include <optional>
#include <vector>

#include "absl/types/span.h"
#include "core/geometry/vec3.h"

namespace membrane {

class ThinPlateSpline {
 public:
  // Input: samples (u, v, height), at least 3 not on one line; `smoothing` >= 0 (0:
  // interpolation; more: an approximation that trades closeness for less bending, for noisy
  // heights), in the samples' units squared. Solves the (n + 3)-square system of
  // h(u, v) = a0 + a1 u + a2 v + sum_i w_i phi(|(u, v) - (u_i, v_i)|), phi(r) = r^2 log r,
  // with sum w_i = sum w_i u_i = sum w_i v_i = 0, by Gaussian elimination with partial pivoting:
  // O(n^3), meant for n up to a few hundred. nullopt when the system is singular (fewer than 3
  // distinct samples, or all on a line) or a value is not finite.
  static std::optional<ThinPlateSpline> Fit(absl::Span<const Vec3d> samples, double smoothing);

  // The height at (u, v): O(n).
  double operator()(double u, double v) const;

 private:
  std::vector<Vec3d> centres_;  // (u_i, v_i, w_i)
  double a_[3] = {0, 0, 0};
};

}  // namespace membrane

#endif  // MEMBRANE_CORE_MESH_THIN_PLATE_SPLINE_H_
