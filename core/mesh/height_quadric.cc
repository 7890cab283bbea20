#include "core/mesh/height_quadric.h"

#include <algorithm>
#include <cmath>

#include "core/geometry/cholesky_solve.h"

namespace membrane {
namespace {

// The basis 1, u, v, u^2, uv, v^2 as powers (i, j) of u^i v^j.
constexpr int kPowU[6] = {0, 1, 0, 2, 1, 0};
constexpr int kPowV[6] = {0, 0, 1, 0, 1, 2};
// A pivot of the normal equations below this fraction of its diagonal entry: they do not
// determine that coefficient.
constexpr double kMinPivot = 1e-7;

}  // namespace

PlaneFitAccumulator HeightFieldSums::PlaneSums() const {
  const int u = Index(1, 0), v = Index(0, 1), uu = Index(2, 0), uvi = Index(1, 1),
            vv = Index(0, 2);
  return PlaneFitAccumulator::FromSums(
      uv[0], {uv[u], uv[v], huv[0]},
      {uv[uu], uv[uvi], huv[Index(1, 0)], uv[vv], huv[Index(0, 1)], hh});
}

std::optional<HeightQuadric> SolveHeightQuadric(const HeightFieldSums& s) {
  if (!(s.weight() > 0)) return std::nullopt;
  // Normal equations M x = r, M[p][q] = sum w phi_p phi_q, r[p] = sum w h phi_p.
  SquareMatrix<6> m;
  HeightQuadric q;
  std::array<double, 6>& r = q.coefficients;
  for (int p = 0; p < 6; ++p) {
    for (int k = 0; k < 6; ++k)
      m[p][k] = s.uv[HeightFieldSums::Index(kPowU[p] + kPowU[k], kPowV[p] + kPowV[k])];
    r[p] = s.huv[HeightFieldSums::Index(kPowU[p], kPowV[p])];
  }
  if (!CholeskySolve(m, r, kMinPivot)) return std::nullopt;
  if (!std::isfinite(q.coefficients[0])) return std::nullopt;
  return q;
}

double QuadricMeanSquareResidual(const HeightFieldSums& s, const HeightQuadric& q) {
  const double w = s.weight();
  if (!(w > 0)) return 0;
  double explained = 0;
  for (int p = 0; p < 6; ++p)
    explained += q.coefficients[p] * s.huv[HeightFieldSums::Index(kPowU[p], kPowV[p])];
  return std::max(0.0, (s.hh - explained) / w);
}

std::optional<HeightQuadric> FitHeightQuadric(const HeightFieldSums& s,
                                              const HeightQuadricLimits& limits) {
  const double w = s.weight();
  if (!(w > 0)) return std::nullopt;
  // Tangential spread: the smaller eigenvalue of the weighted (u, v) covariance.
  const double mu = s.uv[HeightFieldSums::Index(1, 0)] / w,
               mv = s.uv[HeightFieldSums::Index(0, 1)] / w;
  const double cuu = s.uv[HeightFieldSums::Index(2, 0)] / w - mu * mu,
               cuv = s.uv[HeightFieldSums::Index(1, 1)] / w - mu * mv,
               cvv = s.uv[HeightFieldSums::Index(0, 2)] / w - mv * mv;
  const double half_trace = 0.5 * (cuu + cvv);
  const double root = std::sqrt(0.25 * (cuu - cvv) * (cuu - cvv) + cuv * cuv);
  const double spread2 = half_trace - root;
  if (!(spread2 >= limits.min_tangent_spread * limits.min_tangent_spread)) return std::nullopt;
  if (!(mu * mu + mv * mv <= limits.max_centroid_offset * limits.max_centroid_offset * spread2))
    return std::nullopt;

  const std::optional<HeightQuadric> q = SolveHeightQuadric(s);
  if (!q) return std::nullopt;
  const auto& c = q->coefficients;
  if (c[1] * c[1] + c[2] * c[2] > limits.max_slope * limits.max_slope) return std::nullopt;
  const double bend = std::max({std::fabs(2 * c[3]), std::fabs(c[4]), std::fabs(2 * c[5])});
  if (!(bend <= limits.max_curvature)) return std::nullopt;
  return q;
}

}  // namespace membrane
