// Weighted least-squares plane of a few points (membrane-quality.md recipe 3 step 5: "the
// target is the projection on the weighted PCA plane").
#ifndef MEMBRANE_CORE_MESH_PLANE_FIT_H_
#define MEMBRANE_CORE_MESH_PLANE_FIT_H_

#include <array>
#include <optional>

#include "core/geometry/vec3.h"

namespace membrane {

// Accumulates weighted points (coordinates relative to a nearby origin, to keep the sums small).
class PlaneFitAccumulator {
 public:
  void Add(const Vec3d& p, double w) {
    sw_ += w;
    for (int k = 0; k < 3; ++k) s_[k] += w * p[k];
    s2_[0] += w * p[0] * p[0];
    s2_[1] += w * p[0] * p[1];
    s2_[2] += w * p[0] * p[2];
    s2_[3] += w * p[1] * p[1];
    s2_[4] += w * p[1] * p[2];
    s2_[5] += w * p[2] * p[2];
  }
  // The accumulator whose sums are these: total weight `w`, sum of w * p `s`, and sums of
  // w * p_i * p_j in the order xx, xy, xz, yy, yz, zz (as if each point had been Add()ed).
  static PlaneFitAccumulator FromSums(double w, const Vec3d& s, const std::array<double, 6>& s2) {
    PlaneFitAccumulator acc;
    acc.sw_ = w;
    acc.s_ = s;
    acc.s2_ = s2;
    return acc;
  }
  double weight() const { return sw_; }
  // Sum of w * p; divided by weight() it is the weighted centroid.
  Vec3d WeightedSum() const { return s_; }

  struct Plane {
    Vec3d centroid;
    Vec3d normal;  // unit
  };
  // The plane through the weighted centroid normal to the direction of least weighted spread
  // (smallest eigenvector of the covariance). nullopt when the weight is zero or the points
  // do not define a plane (the two smallest spreads are nearly equal: points on a line or a
  // blob).
  std::optional<Plane> Fit() const;

 private:
  double sw_ = 0;
  Vec3d s_{0, 0, 0};
  std::array<double, 6> s2_{};  // xx, xy, xz, yy, yz, zz
};

}  // namespace membrane

#endif  // MEMBRANE_CORE_MESH_PLANE_FIT_H_
