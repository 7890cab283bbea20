// The quadric error metric of Garland and Heckbert ("Surface simplification using quadric error
// metrics", 1997): the sum of squared distances from a point to a set of planes, as one
// symmetric 4x4 matrix. Edge-collapse decimation (mesh_decimation.h) keeps one per vertex.
#ifndef MEMBRANE_CORE_MESH_ERROR_QUADRIC_H_
#define MEMBRANE_CORE_MESH_ERROR_QUADRIC_H_

#include <cmath>

#include "core/geometry/vec3.h"

namespace membrane {

// Q(x) = x^T A x + 2 b.x + c, with A symmetric 3x3 (six entries), in squared model units times
// the weights given.
struct ErrorQuadric {
  double xx = 0, xy = 0, xz = 0, yy = 0, yz = 0, zz = 0;  // A
  double bx = 0, by = 0, bz = 0;                          // b
  double c = 0;

  // `weight` times the squared distance to the plane through `point` with unit normal
  // `normal`: the plane n.x + d = 0 gives A = n n^T, b = d n, c = d^2.
  static ErrorQuadric Plane(const Vec3d& normal, const Vec3d& point, double weight) {
    const double d = -Dot(normal, point);
    const double nx = normal[0], ny = normal[1], nz = normal[2];
    ErrorQuadric q;
    q.xx = weight * nx * nx, q.xy = weight * nx * ny, q.xz = weight * nx * nz;
    q.yy = weight * ny * ny, q.yz = weight * ny * nz, q.zz = weight * nz * nz;
    q.bx = weight * d * nx, q.by = weight * d * ny, q.bz = weight * d * nz;
    q.c = weight * d * d;
    return q;
  }

  ErrorQuadric& operator+=(const ErrorQuadric& o) {
    xx += o.xx, xy += o.xy, xz += o.xz, yy += o.yy, yz += o.yz, zz += o.zz;
    bx += o.bx, by += o.by, bz += o.bz, c += o.c;
    return *this;
  }
  friend ErrorQuadric operator+(ErrorQuadric a, const ErrorQuadric& b) { return a += b; }

  // Q(p); never below 0 in exact arithmetic, so rounding below 0 is returned as 0.
  double Evaluate(const Vec3d& p) const {
    const double x = p[0], y = p[1], z = p[2];
    const double v = xx * x * x + 2 * xy * x * y + 2 * xz * x * z + yy * y * y + 2 * yz * y * z +
                     zz * z * z + 2 * (bx * x + by * y + bz * z) + c;
    return v > 0 ? v : 0;
  }

  // The point where Q is least (A x = -b), when A is well conditioned: false when its
  // determinant is below 1e-9 of its largest possible value for A's trace (planes nearly
  // parallel or along one line: the minimum is a line or a plane, not a point).
  bool Minimizer(Vec3d& out) const {
    const double c00 = yy * zz - yz * yz, c01 = xz * yz - xy * zz, c02 = xy * yz - xz * yy;
    const double det = xx * c00 + xy * c01 + xz * c02;
    const double trace = xx + yy + zz;
    if (!(trace > 0) || !(det > 1e-9 * trace * trace * trace / 27)) return false;
    const double c11 = xx * zz - xz * xz, c12 = xy * xz - xx * yz, c22 = xx * yy - xy * xy;
    const double inv = -1 / det;  // x = A^-1 (-b), A^-1 = adj(A) / det (A symmetric)
    out = {inv * (c00 * bx + c01 * by + c02 * bz), inv * (c01 * bx + c11 * by + c12 * bz),
           inv * (c02 * bx + c12 * by + c22 * bz)};
    return std::isfinite(out[0]) && std::isfinite(out[1]) && std::isfinite(out[2]);
  }
};

}  // namespace membrane

#endif  // MEMBRANE_CORE_MESH_ERROR_QUADRIC_H_
