// Minimal 3-vector arithmetic in double, for the generators' geometry (model units).
#ifndef MEMBRANE_CORE_SYNTH_VEC3_H_
#define MEMBRANE_CORE_SYNTH_VEC3_H_

#include <array>
#include <cmath>

namespace membrane {

using Vec3 = std::array<double, 3>;

// Component-wise a + b, a - b and s a.
inline Vec3 Add(const Vec3& a, const Vec3& b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
inline Vec3 Sub(const Vec3& a, const Vec3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
inline Vec3 Scale(const Vec3& a, double s) { return {a[0] * s, a[1] * s, a[2] * s}; }
// Dot and cross products.
inline double Dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
inline Vec3 Cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
// Euclidean length.
inline double Norm(const Vec3& a) { return std::sqrt(Dot(a, a)); }
// `a` scaled to unit length; `a` must be non-zero.
inline Vec3 Normalized(const Vec3& a) { return Scale(a, 1.0 / Norm(a)); }

}  // namespace membrane

#endif  // MEMBRANE_CORE_SYNTH_VEC3_H_
