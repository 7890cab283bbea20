#include "core/mesh/thin_plate_spline.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace membrane {
namespace {

// r^2 log r from r^2: 0.5 r^2 log r^2, and 0 at r = 0 (its limit).
double Kernel(double r2) { return r2 > 0 ? 0.5 * r2 * std::log(r2) : 0.0; }

}  // namespace

std::optional<ThinPlateSpline> ThinPlateSpline::Fit(absl::Span<const Vec3d> samples,
                                                    double smoothing) {
  const size_t n = samples.size();
  if (n < 3 || !(smoothing >= 0)) return std::nullopt;
  const size_t m = n + 3;
  // Row-major m x (m + 1): the system and its right-hand side.
  std::vector<double> a(m * (m + 1), 0.0);
  auto at = [&](size_t r, size_t c) -> double& { return a[r * (m + 1) + c]; };
  for (size_t i = 0; i < n; ++i) {
    for (size_t j = 0; j < n; ++j) {
      const double du = samples[i][0] - samples[j][0], dv = samples[i][1] - samples[j][1];
      at(i, j) = Kernel(du * du + dv * dv);
    }
    at(i, i) += smoothing;
    const double p[3] = {1.0, samples[i][0], samples[i][1]};
    for (int k = 0; k < 3; ++k) at(i, n + k) = at(n + k, i) = p[k];
    at(i, m) = samples[i][2];
  }
  double scale = 0;
  for (double x : a) {
    if (!std::isfinite(x)) return std::nullopt;
    scale = std::max(scale, std::abs(x));
  }
  for (size_t c = 0; c < m; ++c) {
    size_t pivot = c;
    for (size_t r = c + 1; r < m; ++r)
      if (std::abs(at(r, c)) > std::abs(at(pivot, c))) pivot = r;
    if (!(std::abs(at(pivot, c)) > 1e-12 * scale)) return std::nullopt;
    if (pivot != c)
      for (size_t k = c; k <= m; ++k) std::swap(at(c, k), at(pivot, k));
    const double inv = 1.0 / at(c, c);
    for (size_t r = c + 1; r < m; ++r) {
      const double f = at(r, c) * inv;
      if (f == 0) continue;
      for (size_t k = c; k <= m; ++k) at(r, k) -= f * at(c, k);
    }
  }
  std::vector<double> x(m);
  for (size_t c = m; c-- > 0;) {
    double s = at(c, m);
    for (size_t k = c + 1; k < m; ++k) s -= at(c, k) * x[k];
    x[c] = s / at(c, c);
    if (!std::isfinite(x[c])) return std::nullopt;
  }
  ThinPlateSpline spline;
  spline.centres_.resize(n);
  for (size_t i = 0; i < n; ++i) spline.centres_[i] = {samples[i][0], samples[i][1], x[i]};
  for (int k = 0; k < 3; ++k) spline.a_[k] = x[n + k];
  return spline;
}

double ThinPlateSpline::operator()(double u, double v) const {
  double h = a_[0] + a_[1] * u + a_[2] * v;
  for (const Vec3d& c : centres_) {
    const double du = u - c[0], dv = v - c[1];
    h += c[2] * Kernel(du * du + dv * dv);
  }
  return h;
}

}  // namespace membrane
