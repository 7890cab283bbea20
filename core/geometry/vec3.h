// Double-precision 3-vectors: the geometry of the surface, the mesh check and the shape
// generators (model or lattice units, as the caller's).
//
// Geometry tests run in double on float32 inputs: differences of nearby floats are exact in
// double, so orientation signs are reliable except within rounding of truly degenerate cases.
#ifndef MEMBRANE_CORE_GEOMETRY_VEC3_H_
#define MEMBRANE_CORE_GEOMETRY_VEC3_H_

#include <array>
#include <cmath>

#include "core/geometry/point_cloud.h"

namespace membrane {

using Vec3d = std::array<double, 3>;

inline Vec3d ToVec3d(const Point3f& p) { return {p[0], p[1], p[2]}; }
inline Point3f ToPoint3f(const Vec3d& v) {
  return {static_cast<float>(v[0]), static_cast<float>(v[1]), static_cast<float>(v[2])};
}
// Component-wise a + b, a - b and s a.
inline Vec3d operator+(const Vec3d& a, const Vec3d& b) {
  return {a[0] + b[0], a[1] + b[1], a[2] + b[2]};
}
inline Vec3d operator-(const Vec3d& a, const Vec3d& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
inline Vec3d operator*(double s, const Vec3d& a) { return {s * a[0], s * a[1], s * a[2]}; }
// Dot and cross products.
inline double Dot(const Vec3d& a, const Vec3d& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
inline Vec3d Cross(const Vec3d& a, const Vec3d& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
// Squared and plain Euclidean length.
inline double SquaredNorm(const Vec3d& a) { return Dot(a, a); }
inline double Norm(const Vec3d& a) { return std::sqrt(Dot(a, a)); }
// `a` scaled to unit length; the zero vector for the zero vector.
inline Vec3d Normalized(const Vec3d& a) {
  const double n = Norm(a);
  return n > 0 ? (1.0 / n) * a : Vec3d{0, 0, 0};
}
// Twice the area vector of triangle (a, b, c): its direction is the CCW normal.
inline Vec3d TriangleNormal(const Vec3d& a, const Vec3d& b, const Vec3d& c) {
  return Cross(b - a, c - a);
}

}  // namespace membrane

#endif  // MEMBRANE_CORE_GEOMETRY_VEC3_H_
