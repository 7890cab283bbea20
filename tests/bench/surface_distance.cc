#include "tests/bench/surface_distance.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <utility>

#include "absl/status/status.h"

namespace membrane::bench {
namespace {

constexpr int kLeafSize = 4;

Vec3d Sub(const Vec3d& a, const Vec3d& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
double Dot(const Vec3d& a, const Vec3d& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
Vec3d Cross(const Vec3d& a, const Vec3d& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
Vec3d Madd(const Vec3d& a, double s, const Vec3d& d) {
  return {a[0] + s * d[0], a[1] + s * d[1], a[2] + s * d[2]};
}
double Dist2(const Vec3d& a, const Vec3d& b) {
  const Vec3d d = Sub(a, b);
  return Dot(d, d);
}

// Squared distance from `p` to triangle (a, b, c): the closest point by Voronoi regions
// (Ericson, Real-Time Collision Detection 5.1.5). Exact for degenerate triangles as well.
double PointTriangleDist2(const Vec3d& p, const Vec3d& a, const Vec3d& b, const Vec3d& c) {
  const Vec3d ab = Sub(b, a), ac = Sub(c, a), ap = Sub(p, a);
  const double d1 = Dot(ab, ap), d2 = Dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return Dot(ap, ap);
  const Vec3d bp = Sub(p, b);
  const double d3 = Dot(ab, bp), d4 = Dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return Dot(bp, bp);
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double den = d1 - d3;
    return Dist2(p, Madd(a, den > 0 ? d1 / den : 0, ab));
  }
  const Vec3d cp = Sub(p, c);
  const double d5 = Dot(ab, cp), d6 = Dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return Dot(cp, cp);
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double den = d2 - d6;
    return Dist2(p, Madd(a, den > 0 ? d2 / den : 0, ac));
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const double den = (d4 - d3) + (d5 - d6);
    return Dist2(p, Madd(b, den > 0 ? (d4 - d3) / den : 0, Sub(c, b)));
  }
  const double sum = va + vb + vc;
  if (!(sum > 0)) {  // degenerate (collinear): the nearest of the three edges
    auto seg = [&](const Vec3d& u, const Vec3d& v) {
      const Vec3d uv = Sub(v, u);
      const double len2 = Dot(uv, uv);
      const double t = len2 > 0 ? std::clamp(Dot(Sub(p, u), uv) / len2, 0.0, 1.0) : 0.0;
      return Dist2(p, Madd(u, t, uv));
    };
    return std::min({seg(a, b), seg(b, c), seg(c, a)});
  }
  const double v = vb / sum, w = vc / sum;
  return Dist2(p, Madd(Madd(a, v, ab), w, ac));
}

double BoxDist2(const Vec3d& p, const Vec3d& lo, const Vec3d& hi) {
  double d2 = 0;
  for (int k = 0; k < 3; ++k) {
    const double d = p[k] < lo[k] ? lo[k] - p[k] : p[k] > hi[k] ? p[k] - hi[k] : 0.0;
    d2 += d * d;
  }
  return d2;
}

Vec3d ToVec(const Point3f& p) { return {p[0], p[1], p[2]}; }

bool ValidFace(const TriangleMesh& mesh, const std::array<int32_t, 3>& f) {
  const int64_t n = static_cast<int64_t>(mesh.vertices.size());
  return f[0] >= 0 && f[1] >= 0 && f[2] >= 0 && f[0] < n && f[1] < n && f[2] < n;
}

double Percentile(std::vector<double>& v, double q) {
  if (v.empty()) return 0;
  const size_t k = std::min(v.size() - 1, static_cast<size_t>(std::ceil(q * v.size())) - 1);
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
  return v[k];
}

}  // namespace

TriangleDistance::TriangleDistance(const TriangleMesh& mesh) {
  tris_.reserve(mesh.faces.size());
  for (const auto& f : mesh.faces) {
    if (!ValidFace(mesh, f)) continue;
    tris_.push_back({ToVec(mesh.vertices[f[0]]), ToVec(mesh.vertices[f[1]]),
                     ToVec(mesh.vertices[f[2]])});
  }
  if (tris_.empty()) return;
  std::vector<Vec3d> centroids(tris_.size());
  for (size_t i = 0; i < tris_.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      centroids[i][k] = (tris_[i][0][k] + tris_[i][1][k] + tris_[i][2][k]) / 3.0;
    }
  }
  nodes_.reserve(2 * tris_.size() / kLeafSize + 2);
  Build(0, static_cast<int32_t>(tris_.size()), centroids);
}

int32_t TriangleDistance::Build(int32_t first, int32_t count, std::vector<Vec3d>& centroids) {
  const int32_t index = static_cast<int32_t>(nodes_.size());
  nodes_.push_back({});
  Node node;
  const double inf = std::numeric_limits<double>::infinity();
  node.lo = {inf, inf, inf};
  node.hi = {-inf, -inf, -inf};
  Vec3d clo = node.lo, chi = node.hi;
  for (int32_t i = first; i < first + count; ++i) {
    for (const Vec3d& v : tris_[i]) {
      for (int k = 0; k < 3; ++k) {
        node.lo[k] = std::min(node.lo[k], v[k]);
        node.hi[k] = std::max(node.hi[k], v[k]);
      }
    }
    for (int k = 0; k < 3; ++k) {
      clo[k] = std::min(clo[k], centroids[i][k]);
      chi[k] = std::max(chi[k], centroids[i][k]);
    }
  }
  if (count <= kLeafSize) {
    node.first = first;
    node.count = count;
    nodes_[index] = node;
    return index;
  }
  int axis = 0;
  for (int k = 1; k < 3; ++k) {
    if (chi[k] - clo[k] > chi[axis] - clo[axis]) axis = k;
  }
  const int32_t half = count / 2;
  // Sort triangles and their centroids together by the centroid on `axis` (median split).
  std::vector<int32_t> order(static_cast<size_t>(count));
  for (int32_t i = 0; i < count; ++i) order[i] = first + i;
  std::nth_element(order.begin(), order.begin() + half, order.end(), [&](int32_t a, int32_t b) {
    return centroids[a][axis] < centroids[b][axis];
  });
  std::vector<std::array<Vec3d, 3>> tris(static_cast<size_t>(count));
  std::vector<Vec3d> cents(static_cast<size_t>(count));
  for (int32_t i = 0; i < count; ++i) {
    tris[i] = tris_[order[i]];
    cents[i] = centroids[order[i]];
  }
  std::copy(tris.begin(), tris.end(), tris_.begin() + first);
  std::copy(cents.begin(), cents.end(), centroids.begin() + first);
  node.left = Build(first, half, centroids);
  node.right = Build(first + half, count - half, centroids);
  nodes_[index] = node;
  return index;
}

double TriangleDistance::Distance(const Vec3d& p) const {
  double best = std::numeric_limits<double>::infinity();
  if (nodes_.empty()) return best;
  std::vector<std::pair<double, int32_t>> stack;  // (box distance^2, node)
  stack.reserve(64);
  stack.push_back({BoxDist2(p, nodes_[0].lo, nodes_[0].hi), 0});
  while (!stack.empty()) {
    const auto [d2, index] = stack.back();
    stack.pop_back();
    if (d2 >= best) continue;
    const Node& n = nodes_[index];
    if (n.left < 0) {
      for (int32_t i = n.first; i < n.first + n.count; ++i) {
        best = std::min(best, PointTriangleDist2(p, tris_[i][0], tris_[i][1], tris_[i][2]));
      }
      continue;
    }
    const double dl = BoxDist2(p, nodes_[n.left].lo, nodes_[n.left].hi);
    const double dr = BoxDist2(p, nodes_[n.right].lo, nodes_[n.right].hi);
    // Push the farther first so the nearer is searched first.
    if (dl < dr) {
      if (dr < best) stack.push_back({dr, n.right});
      if (dl < best) stack.push_back({dl, n.left});
    } else {
      if (dl < best) stack.push_back({dl, n.left});
      if (dr < best) stack.push_back({dr, n.right});
    }
  }
  return std::sqrt(best);
}

std::vector<Vec3d> SampleSurface(const TriangleMesh& mesh, int64_t count, uint64_t seed) {
  std::vector<double> cumulative;
  std::vector<int32_t> face_of;
  cumulative.reserve(mesh.faces.size());
  face_of.reserve(mesh.faces.size());
  double total = 0;
  for (size_t i = 0; i < mesh.faces.size(); ++i) {
    const auto& f = mesh.faces[i];
    if (!ValidFace(mesh, f)) continue;
    const Vec3d a = ToVec(mesh.vertices[f[0]]);
    const Vec3d n = Cross(Sub(ToVec(mesh.vertices[f[1]]), a), Sub(ToVec(mesh.vertices[f[2]]), a));
    const double area = 0.5 * std::sqrt(Dot(n, n));
    if (!(area > 0)) continue;
    total += area;
    cumulative.push_back(total);
    face_of.push_back(static_cast<int32_t>(i));
  }
  std::vector<Vec3d> samples;
  if (!(total > 0) || count <= 0) return samples;
  samples.reserve(static_cast<size_t>(count));
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int64_t s = 0; s < count; ++s) {
    const double r = unit(rng) * total;
    size_t k = static_cast<size_t>(std::upper_bound(cumulative.begin(), cumulative.end(), r) -
                                   cumulative.begin());
    k = std::min(k, cumulative.size() - 1);
    const auto& f = mesh.faces[face_of[k]];
    const Vec3d a = ToVec(mesh.vertices[f[0]]), b = ToVec(mesh.vertices[f[1]]),
                c = ToVec(mesh.vertices[f[2]]);
    const double r1 = std::sqrt(unit(rng)), r2 = unit(rng);
    const double u = 1 - r1, v = r1 * (1 - r2), w = r1 * r2;
    samples.push_back({u * a[0] + v * b[0] + w * c[0], u * a[1] + v * b[1] + w * c[1],
                       u * a[2] + v * b[2] + w * c[2]});
  }
  return samples;
}

absl::StatusOr<SurfaceDistances> CompareSurfaces(const TriangleMesh& recon,
                                                 const TriangleMesh& reference, int64_t samples,
                                                 double fscore_tau_percent) {
  SurfaceDistances out;
  if (reference.vertices.empty()) return absl::InvalidArgumentError("empty reference mesh");
  Vec3d lo = ToVec(reference.vertices[0]), hi = lo;
  for (const Point3f& v : reference.vertices) {
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], static_cast<double>(v[k]));
      hi[k] = std::max(hi[k], static_cast<double>(v[k]));
    }
  }
  out.diagonal = std::sqrt(Dist2(lo, hi));
  const std::vector<Vec3d> recon_samples = SampleSurface(recon, samples, 12345);
  const std::vector<Vec3d> ref_samples = SampleSurface(reference, samples, 67890);
  if (recon_samples.empty()) return absl::InvalidArgumentError("reconstruction has no area");
  if (ref_samples.empty() || !(out.diagonal > 0)) {
    return absl::InvalidArgumentError("reference mesh has no area");
  }
  const TriangleDistance to_ref(reference), to_recon(recon);
  const double tau = fscore_tau_percent / 100.0 * out.diagonal;
  std::vector<double> pooled;
  pooled.reserve(recon_samples.size() + ref_samples.size());
  double sum_a = 0, sum_b = 0, max_d = 0;
  int64_t near_a = 0, near_b = 0;
  for (const Vec3d& p : recon_samples) {
    const double d = to_ref.Distance(p);
    sum_a += d;
    near_a += d <= tau;
    max_d = std::max(max_d, d);
    pooled.push_back(d);
  }
  for (const Vec3d& p : ref_samples) {
    const double d = to_recon.Distance(p);
    sum_b += d;
    near_b += d <= tau;
    max_d = std::max(max_d, d);
    pooled.push_back(d);
  }
  const double pct = 100.0 / out.diagonal;
  out.to_reference = pct * sum_a / static_cast<double>(recon_samples.size());
  out.to_recon = pct * sum_b / static_cast<double>(ref_samples.size());
  out.chamfer = 0.5 * (out.to_reference + out.to_recon);
  out.p95 = pct * Percentile(pooled, 0.95);
  out.hausdorff = pct * max_d;
  out.fscore_tau = fscore_tau_percent;
  out.precision = static_cast<double>(near_a) / static_cast<double>(recon_samples.size());
  out.recall = static_cast<double>(near_b) / static_cast<double>(ref_samples.size());
  const double pr = out.precision + out.recall;
  out.fscore = pr > 0 ? 2 * out.precision * out.recall / pr : 0.0;
  return out;
}

}  // namespace membrane::bench
