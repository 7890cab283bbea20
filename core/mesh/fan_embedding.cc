#include "core/mesh/fan_embedding.h"

#include <algorithm>
#include <cmath>

namespace membrane {
namespace {

// Relative margin of every sign decision: rounding errors of these few products and sums are
// below 1e-14 of the scales they are compared with.
constexpr double kMargin = 1e-9;

}  // namespace

bool FanIsEmbedded(const Vec3d& centre, absl::Span<const Vec3d> ring) {
  const size_t k = ring.size();
  if (k < 3) return false;
  // Edges from the centre and the face normals, as TriangleNormal(centre, ring[i], ring[i+1]).
  constexpr size_t kMaxFan = 32;
  if (k > kMaxFan) return false;
  Vec3d edge[kMaxFan], normal[kMaxFan];
  for (size_t i = 0; i < k; ++i) edge[i] = ring[i] - centre;
  Vec3d sum{0, 0, 0};
  double norm_sum = 0;
  double norm[kMaxFan];
  for (size_t i = 0; i < k; ++i) {
    normal[i] = Cross(edge[i], edge[(i + 1) % k]);
    norm[i] = Norm(normal[i]);
    sum = sum + normal[i];
    norm_sum += norm[i];
  }
  // Every face positively oriented seen along `sum`: its angular sector around the centre,
  // from ring[i] to ring[i+1] counter-clockwise, is less than a half turn.
  for (size_t i = 0; i < k; ++i)
    if (!(Dot(normal[i], sum) > kMargin * norm[i] * norm_sum)) return false;
  // The sectors then add up to a whole number of turns: count how often the ring passes a ray
  // `d` (from ring[i] before the ray to ring[i+1] after it). The ray runs inside the first
  // sector, between its two edges (its part along `sum` does not matter): an axis-aligned ray
  // would graze the axis-aligned edges of surface nets on flat parts.
  const Vec3d d = (1 / Norm(edge[0])) * edge[0] + (1 / Norm(edge[1])) * edge[1];
  const double d_norm = Norm(d);
  const double sum_sq = SquaredNorm(sum);
  bool before[kMaxFan];
  for (size_t i = 0; i < k; ++i) {
    // > 0: the ray is counter-clockwise from ring[i] within a half turn.
    const double s = Dot(sum, Cross(edge[i], d));
    before[i] = s > 0;
    if (std::fabs(s) > kMargin * norm_sum * Norm(edge[i]) * d_norm) continue;
    // ring[i] lies (nearly) on the line of the ray. Opposite the ray, either side counts the
    // same passes of the ray; on the ray itself the count would be a guess.
    const double along = Dot(edge[i], d) * sum_sq - Dot(edge[i], sum) * Dot(d, sum);
    if (!(along < -kMargin * Norm(edge[i]) * d_norm * sum_sq)) return false;
  }
  int turns = 0;
  for (size_t i = 0; i < k; ++i) turns += before[i] && !before[(i + 1) % k];
  return turns == 1;
}

MeshFans::MeshFans(const TriangleMesh& mesh) {
  const int32_t nv = static_cast<int32_t>(mesh.vertices.size());
  // Per vertex, its faces as (previous, next) neighbour pairs: face (v, a, b) sends a to b.
  std::vector<int32_t> count(nv + 1, 0);
  for (const auto& f : mesh.faces)
    for (int32_t v : f)
      if (v >= 0 && v < nv) ++count[v + 1];
  for (int32_t v = 0; v < nv; ++v) count[v + 1] += count[v];
  std::vector<std::pair<int32_t, int32_t>> step(count[nv]);
  std::vector<int32_t> fill(count.begin(), count.end() - 1);
  for (const auto& f : mesh.faces) {
    bool valid = true;
    for (int32_t v : f) valid = valid && v >= 0 && v < nv;
    if (!valid) continue;
    for (int k = 0; k < 3; ++k) step[fill[f[k]]++] = {f[(k + 1) % 3], f[(k + 2) % 3]};
  }
  start_.assign(nv + 1, 0);
  ring_.reserve(step.size());
  for (int32_t v = 0; v < nv; ++v) {
    const size_t begin = ring_.size();
    const int32_t n = count[v + 1] - count[v];
    const auto* s = step.data() + count[v];
    // Follow a -> b from the first face; a closed fan visits every face once and comes back.
    // A neighbour met twice as an `a` (or as a `b`) means two fans glued at the vertex.
    bool fan = n >= 3;
    for (int32_t i = 0; fan && i < n; ++i)
      for (int32_t j = i + 1; fan && j < n; ++j)
        fan = s[i].first != s[j].first && s[i].second != s[j].second;
    // The steps are then one-to-one, so the walk can only come back to its start: too early
    // means more than one cycle.
    const int32_t start = fan ? s[0].first : -1;
    int32_t a = start;
    for (int32_t visited = 0; fan && visited < n; ++visited) {
      if (visited > 0 && a == start) {
        fan = false;
        break;
      }
      ring_.push_back(a);
      int32_t j = 0;
      while (j < n && s[j].first != a) ++j;
      fan = j < n;
      if (fan) a = s[j].second;
    }
    if (!fan || a != start) ring_.resize(begin);
    start_[v + 1] = static_cast<int32_t>(ring_.size());
  }
}

}  // namespace membrane
