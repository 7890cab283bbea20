#include "core/mesh/fan_embedding.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

#include "core/base/parallel_tasks.h"

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

namespace {

// Below this many vertices the fans are walked on the calling thread.
constexpr int64_t kMinRangeVertices = int64_t{1} << 16;

// The faces of `mesh` whose vertex ids are all in range: the rings read the faces' vertices,
// never their indices, so the others can be left out.
std::vector<std::array<int32_t, 3>> FacesInRange(const TriangleMesh& mesh) {
  const int64_t nv = static_cast<int64_t>(mesh.vertices.size());
  std::vector<std::array<int32_t, 3>> faces;
  faces.reserve(mesh.faces.size());
  for (const auto& f : mesh.faces) {
    bool valid = true;
    for (int32_t v : f) valid = valid && v >= 0 && v < nv;
    if (valid) faces.push_back(f);
  }
  return faces;
}

}  // namespace

MeshFans::MeshFans(const TriangleMesh& mesh) {
  const std::vector<std::array<int32_t, 3>> faces = FacesInRange(mesh);
  WalkFans(faces, FacesAroundVertices(faces, static_cast<int32_t>(mesh.vertices.size()), 1), 1);
}

MeshFans::MeshFans(const std::vector<std::array<int32_t, 3>>& faces, const VertexStars& stars,
                   int threads) {
  WalkFans(faces, stars, threads);
}

void MeshFans::WalkFans(const std::vector<std::array<int32_t, 3>>& faces,
                        const VertexStars& stars, int threads) {
  const int64_t nv = static_cast<int64_t>(stars.start.size()) - 1;
  start_.resize(static_cast<size_t>(nv));
  size_.resize(static_cast<size_t>(nv));
  ring_.resize(stars.faces.size());
  const int64_t ranges = threads > 1 && nv >= kMinRangeVertices ? 4 * int64_t{threads} : 1;
  RunTasks(threads, ranges, [&](int, int64_t r) {
    // Per vertex, its faces as (previous, next) neighbour pairs in the star's order: face
    // (v, a, b) sends a to b. A face listing v twice is in the star twice, in a row: its second
    // entry takes v's next corner.
    std::vector<std::pair<int32_t, int32_t>> s;
    for (int64_t v = r * nv / ranges; v < (r + 1) * nv / ranges; ++v) {
      const int32_t first = stars.start[static_cast<size_t>(v)];
      const int32_t n = stars.start[static_cast<size_t>(v) + 1] - first;
      s.clear();
      int corner = -1;
      for (int32_t i = 0; i < n; ++i) {
        const int32_t face = stars.faces[static_cast<size_t>(first + i)];
        const auto& f = faces[static_cast<size_t>(face)];
        const bool again = i > 0 && stars.faces[static_cast<size_t>(first + i - 1)] == face;
        int k = again ? corner + 1 : 0;
        while (f[k] != v) ++k;
        corner = k;
        s.push_back({f[(k + 1) % 3], f[(k + 2) % 3]});
      }
      start_[static_cast<size_t>(v)] = first;
      int32_t* const ring = ring_.data() + first;
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
        ring[visited] = a;
        int32_t j = 0;
        while (j < n && s[j].first != a) ++j;
        fan = j < n;
        if (fan) a = s[j].second;
      }
      size_[static_cast<size_t>(v)] = fan && a == start ? n : 0;
    }
  });
}

}  // namespace membrane
