// An algebraic sphere fitted to oriented points (Guennebaud and Gross 2007, "Algebraic point set
// surfaces"): the zero set of s(p) = u0 + ul . p + u4 |p|^2 whose gradient best matches the
// points' normals and which passes closest to the points; a plane where u4 is 0. For the hole
// caps (hole_caps.h): the band of data around a hole extrapolates its own curvature across it.
#ifndef MEMBRANE_CORE_MESH_ALGEBRAIC_SPHERE_H_
#define MEMBRANE_CORE_MESH_ALGEBRAIC_SPHERE_H_

#include <optional>

#include "absl/types/span.h"
#include "core/geometry/vec3.h"

namespace membrane {

class AlgebraicSphere {
 public:
  // Input: positions and their unit normals (outward), the same count. Uniform weights, in two
  // linear least-squares steps (the paper's closed form): ul and u4 from the normals (the
  // gradient ul + 2 u4 p against n at every point), then u0 from the positions (the mean of s
  // at the points is 0). nullopt when the positions do not spread (fewer than 2 distinct), the
  // counts differ, the gradient vanishes, the sphere is imaginary or a value is not finite.
  static std::optional<AlgebraicSphere> Fit(absl::Span<const Vec3d> positions,
                                            absl::Span<const Vec3d> normals);

  // The Euclidean distance of p from the sphere (or the plane), >= 0.
  double Distance(const Vec3d& p) const;

  // The signed radius (positive: convex toward the normals, a ball; negative: concave); 0 for
  // a plane.
  double radius() const { return radius_; }

 private:
  Vec3d origin_{0, 0, 0};  // the positions' centroid: p is taken relative to it
  Vec3d linear_{0, 0, 0};  // ul
  double constant_ = 0;    // u0
  double quadratic_ = 0;   // u4
  Vec3d centre_{0, 0, 0};  // relative to origin_, when quadratic_ != 0
  double radius_ = 0;
};

}  // namespace membrane

#endif  // MEMBRANE_CORE_MESH_ALGEBRAIC_SPHERE_H_
