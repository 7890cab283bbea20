#include "core/engine/covariance_eigen.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace membrane {

double SmallestEigenvalue(const SymmetricMatrix3& m) {
  const auto [a, b, c, d, e, f] = m;
  const double q = (a + d + f) / 3;
  const double off = b * b + c * c + e * e;
  const double p2 = (a - q) * (a - q) + (d - q) * (d - q) + (f - q) * (f - q) + 2 * off;
  if (p2 <= 0) return q;  // a multiple of the identity
  const double p = std::sqrt(p2 / 6);
  const double ma = (a - q) / p, mb = b / p, mc = c / p, md = (d - q) / p, me = e / p,
               mf = (f - q) / p;
  const double det = ma * (md * mf - me * me) - mb * (mb * mf - me * mc) + mc * (mb * me - md * mc);
  const double phi = std::acos(std::clamp(det / 2, -1.0, 1.0)) / 3;
  return q + 2 * p * std::cos(phi + 2 * std::numbers::pi / 3);
}

bool SmallestEigenvector(const SymmetricMatrix3& m, std::array<double, 3>& v) {
  const double lambda = SmallestEigenvalue(m);
  // The eigenvector spans the null space of m - lambda I: the largest cross product of two of
  // its rows (any two independent rows give it; the largest is the best conditioned).
  const std::array<std::array<double, 3>, 3> r = {{{m[0] - lambda, m[1], m[2]},
                                                    {m[1], m[3] - lambda, m[4]},
                                                    {m[2], m[4], m[5] - lambda}}};
  double best = 0;
  for (int i = 0; i < 3; ++i) {
    const auto& u = r[i];
    const auto& w = r[(i + 1) % 3];
    const std::array<double, 3> x = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2],
                                     u[0] * w[1] - u[1] * w[0]};
    const double len2 = x[0] * x[0] + x[1] * x[1] + x[2] * x[2];
    if (len2 > best) {
      best = len2;
      const double inv = 1 / std::sqrt(len2);
      v = {x[0] * inv, x[1] * inv, x[2] * inv};
    }
  }
  return best > 0;
}

}  // namespace membrane
