#include "core/mesh/crease_fit.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/geometry/cholesky_solve.h"

namespace membrane {
namespace {

// A pivot of a plane's normal equations below this fraction of its diagonal entry: the side's
// points do not pin the plane down (a strip along the crease).
constexpr double kMinPivot = 1e-6;
constexpr int kMaxRounds = 12;

double PlaneAt(const std::array<double, 3>& c, double u, double v) {
  return c[0] + c[1] * u + c[2] * v;
}

// The weighted least-squares plane h = c0 + c1 u + c2 v of the points with side[i] == s.
std::optional<std::array<double, 3>> FitSide(absl::Span<const FramePoint> points,
                                             const std::vector<char>& side, char s) {
  SquareMatrix<3> m{};
  std::array<double, 3> r{};
  for (size_t i = 0; i < points.size(); ++i) {
    if (side[i] != s) continue;
    const FramePoint& p = points[i];
    const double phi[3] = {1, p.u, p.v};
    for (int a = 0; a < 3; ++a) {
      for (int b = 0; b <= a; ++b) m[a][b] += p.w * phi[a] * phi[b];
      r[a] += p.w * p.h * phi[a];
    }
  }
  if (!CholeskySolve(m, r, kMinPivot)) return std::nullopt;
  if (!std::isfinite(r[0]) || !std::isfinite(r[1]) || !std::isfinite(r[2])) return std::nullopt;
  return r;
}

}  // namespace

bool CreaseWorthTrying(double quadric_rms, const CreaseLimits& limits) {
  return quadric_rms >= std::max(limits.min_quadric_rms, limits.noise_trigger * limits.noise);
}

std::optional<CreaseFit> FitCrease(absl::Span<const FramePoint> points,
                                   const HeightQuadric& quadric, double quadric_rms,
                                   const CreaseLimits& limits) {
  if (!CreaseWorthTrying(quadric_rms, limits) || points.size() < 2u * limits.min_side_points)
    return std::nullopt;
  // The first split: across the direction the quadric bends most, through the point where its
  // slope along that direction is zero (the ridge or valley of the quadric).
  const auto& c = quadric.coefficients;
  const double huu = 2 * c[3], huv = c[4], hvv = 2 * c[5];
  const double half_trace = 0.5 * (huu + hvv);
  const double root = std::sqrt(0.25 * (huu - hvv) * (huu - hvv) + huv * huv);
  const double lambda = std::fabs(half_trace + root) >= std::fabs(half_trace - root)
                            ? half_trace + root
                            : half_trace - root;
  if (!(std::fabs(lambda) > 0)) return std::nullopt;
  // Eigenvector of [[huu, huv], [huv, hvv]] for lambda.
  double tu = huv, tv = lambda - huu;
  if (std::fabs(tu) + std::fabs(tv) < 1e-12 * (std::fabs(huu) + std::fabs(hvv))) {
    tu = lambda - hvv;
    tv = huv;
  }
  const double tn = std::hypot(tu, tv);
  if (!(tn > 0)) return std::nullopt;
  tu /= tn;
  tv /= tn;
  const double s0 = -(c[1] * tu + c[2] * tv) / lambda;
  std::vector<char> side(points.size());
  for (size_t i = 0; i < points.size(); ++i)
    side[i] = points[i].u * tu + points[i].v * tv >= s0 ? 1 : 0;

  std::array<double, 3> a{}, b{};
  for (int round = 0; round < kMaxRounds; ++round) {
    const auto fa = FitSide(points, side, 0);
    const auto fb = FitSide(points, side, 1);
    if (!fa || !fb) return std::nullopt;
    a = *fa;
    b = *fb;
    bool changed = false;
    for (size_t i = 0; i < points.size(); ++i) {
      const FramePoint& p = points[i];
      const char nearer =
          std::fabs(p.h - PlaneAt(a, p.u, p.v)) <= std::fabs(p.h - PlaneAt(b, p.u, p.v)) ? 0 : 1;
      changed |= nearer != side[i];
      side[i] = nearer;
    }
    if (!changed) break;
  }
  // Each side holds enough of the points.
  double total = 0, weight_a = 0;
  int count_a = 0;
  for (size_t i = 0; i < points.size(); ++i) {
    total += points[i].w;
    if (side[i] == 0) {
      weight_a += points[i].w;
      ++count_a;
    }
  }
  const int count_b = static_cast<int>(points.size()) - count_a;
  if (count_a < limits.min_side_points || count_b < limits.min_side_points) return std::nullopt;
  if (!(weight_a >= limits.min_side_share * total) ||
      !(total - weight_a >= limits.min_side_share * total))
    return std::nullopt;
  // The planes' normals (-c1, -c2, 1) far enough apart.
  const Vec3d na{-a[1], -a[2], 1}, nb{-b[1], -b[2], 1};
  const double cosine = Dot(na, nb) / (Norm(na) * Norm(nb));
  if (!(cosine <= std::cos(limits.min_angle_degrees * std::numbers::pi / 180))) return std::nullopt;
  // The envelope that explains the points: the lower plane (a ridge) or the upper (a valley).
  double lower = 0, upper = 0;
  for (const FramePoint& p : points) {
    const double ha = PlaneAt(a, p.u, p.v), hb = PlaneAt(b, p.u, p.v);
    const double dl = p.h - std::min(ha, hb), du = p.h - std::max(ha, hb);
    lower += p.w * dl * dl;
    upper += p.w * du * du;
  }
  CreaseFit fit;
  fit.first = a;
  fit.second = b;
  fit.ridge = lower <= upper;
  fit.rms = std::sqrt((fit.ridge ? lower : upper) / total);
  const double explained =
      std::max(limits.max_rms_ratio * quadric_rms,
               std::min(limits.noise_accept * limits.noise, limits.max_noisy_ratio * quadric_rms));
  if (!(fit.rms <= explained)) return std::nullopt;
  // The crease line's point nearest the vertex: p = alpha na + beta nb with na.p = a0 and
  // nb.p = b0 (each plane is n.p = c0 in (u, v, h)).
  const double aa = Dot(na, na), ab = Dot(na, nb), bb = Dot(nb, nb);
  const double det = aa * bb - ab * ab;
  if (det > 0) {
    const double alpha = (a[0] * bb - b[0] * ab) / det, beta = (b[0] * aa - a[0] * ab) / det;
    const Vec3d on_line = alpha * na + beta * nb;
    if (std::hypot(on_line[0], on_line[1]) <= limits.snap_distance) {
      fit.on_line = true;
      fit.target = on_line;
      return fit;
    }
  }
  fit.target = Vec3d{0, 0, fit.ridge ? std::min(a[0], b[0]) : std::max(a[0], b[0])};
  return fit;
}

}  // namespace membrane
