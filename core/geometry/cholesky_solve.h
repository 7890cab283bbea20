// The solve of a small symmetric positive definite system: the normal equations of a
// least-squares fit (a vertex's height quadric, a noise box's quadric), where Cholesky needs no
// pivoting and half the work of Gaussian elimination.
#ifndef MEMBRANE_CORE_GEOMETRY_CHOLESKY_SOLVE_H_
#define MEMBRANE_CORE_GEOMETRY_CHOLESKY_SOLVE_H_

#include <array>
#include <cmath>
#include <cstddef>

namespace membrane {

template <size_t N>
using SquareMatrix = std::array<std::array<double, N>, N>;

// Solves a x = b, with x written over b, for a symmetric positive definite `a` of which only
// the lower triangle is read; `a` is left holding its Cholesky factor L (a = L L^T) in that
// triangle. False, with `b` unspecified, when a pivot (the part of a diagonal entry that the
// earlier unknowns leave unexplained) is not above `min_pivot_of_diagonal` times that entry,
// nor above `min_pivot`: that unknown is not determined (dependent columns, points that do not
// pin a fit down), `a` is not positive definite, or an entry is not finite. A success never
// divides by a pivot <= 0: a singular system fails, it does not return NaN.
template <size_t N>
bool CholeskySolve(SquareMatrix<N>& a, std::array<double, N>& b, double min_pivot_of_diagonal,
                   double min_pivot = 0) {
  for (size_t k = 0; k < N; ++k) {
    const double diagonal = a[k][k];
    double d = diagonal;
    for (size_t j = 0; j < k; ++j) d -= a[k][j] * a[k][j];
    if (!(d > min_pivot_of_diagonal * diagonal) || !(d > min_pivot)) return false;
    const double l = std::sqrt(d);
    a[k][k] = l;
    for (size_t i = k + 1; i < N; ++i) {
      double x = a[i][k];
      for (size_t j = 0; j < k; ++j) x -= a[i][j] * a[k][j];
      a[i][k] = x / l;
    }
  }
  // L y = b, then L^T x = y, each over b.
  for (size_t i = 0; i < N; ++i) {
    double x = b[i];
    for (size_t j = 0; j < i; ++j) x -= a[i][j] * b[j];
    b[i] = x / a[i][i];
  }
  for (size_t i = N; i-- > 0;) {
    double x = b[i];
    for (size_t j = i + 1; j < N; ++j) x -= a[j][i] * b[j];
    b[i] = x / a[i][i];
  }
  return true;
}

}  // namespace membrane

#endif  // MEMBRANE_CORE_GEOMETRY_CHOLESKY_SOLVE_H_
