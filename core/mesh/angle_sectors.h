// Which of n equal sectors around a point a direction falls in, as the arctangent says, at a
// fraction of its cost: the concave-corner crease (corner_crease.h) bins the band around every
// cap vertex, and the library's atan2 was half of a 10M-point scan's crease.
#ifndef MEMBRANE_CORE_MESH_ANGLE_SECTORS_H_
#define MEMBRANE_CORE_MESH_ANGLE_SECTORS_H_

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

namespace membrane {

// Sector k of n covers the angles [-pi + 2 pi k / n, -pi + 2 pi (k + 1) / n).
class AngleSectors {
 public:
  // 1 <= n <= 360.
  explicit AngleSectors(int n) : n_(n) {
    for (int k = 0; k <= n; ++k) {
      const double angle = -kPi + 2 * kPi * k / n;
      boundary_.push_back({std::cos(angle), std::sin(angle)});
    }
  }

  // Returns min(n - 1, floor((atan2(y, x) + pi) / (2 pi) * n)) for finite y, x: the same
  // integer as that expression with the library's atan2 for every input. A direction more than
  // 1e-12 radians from every boundary it is compared with is placed by a binary search over
  // the boundaries of its half turn (two products each); one nearer, or on the x axis, by the
  // library, whose rounding (about 1e-16 radians) decides there.
  int operator()(double y, double x) const {
    const double r = std::abs(x) + std::abs(y);
    if (y != 0) {
      // The sector is the last boundary k at or before the direction. Below the x axis it lies
      // in [0, ceil(n/2) - 1], above it in [floor(n/2), n - 1]; the first of either range
      // always is at or before it, and each other boundary of the range lies within half a
      // turn of it, so the side of the boundary it is on (the sign of their cross product)
      // orders the two.
      int lo = y < 0 ? 0 : n_ / 2;
      int hi = y < 0 ? (n_ + 1) / 2 - 1 : n_ - 1;
      bool near = false;
      while (lo < hi && !near) {
        const int mid = (lo + hi + 1) / 2;
        const double cross = boundary_[mid].x * y - boundary_[mid].y * x;
        near = std::abs(cross) <= kMargin * r;
        if (cross > 0) {
          lo = mid;
        } else {
          hi = mid - 1;
        }
      }
      if (!near && std::abs(boundary_[lo].x * y - boundary_[lo].y * x) > kMargin * r)
        return std::min(n_ - 1, lo);
    }
    return std::min(n_ - 1, static_cast<int>((std::atan2(y, x) + kPi) / (2 * kPi) * n_));
  }

 private:
  static constexpr double kPi = std::numbers::pi;
  static constexpr double kMargin = 1e-12;
  struct Direction {
    double x, y;
  };

  int n_;
  std::vector<Direction> boundary_;
};

}  // namespace membrane

#endif  // MEMBRANE_CORE_MESH_ANGLE_SECTORS_H_
