#include "core/mesh/corner_crease.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace membrane {
namespace {

constexpr double kPi = 3.14159265358979323846;

// A sector's band members around a position: the nearest `keep` (nearest first) and the sum
// of every member's position.
struct Sector {
  std::vector<double> d2;
  std::vector<int> member;
  Vec3d all{0, 0, 0};
  int count = 0;

  void Clear() {
    d2.clear();
    member.clear();
    all = Vec3d{0, 0, 0};
    count = 0;
  }
  void Add(const Vec3d& position, double d, int i, int keep) {
    all = all + position;
    ++count;
    if (static_cast<int>(d2.size()) == keep && !(d < d2.back())) return;
    size_t at = d2.size();
    if (static_cast<int>(d2.size()) < keep) {
      d2.push_back(d);
      member.push_back(i);
    } else {
      --at;
    }
    for (; at > 0 && d2[at - 1] > d; --at) {
      d2[at] = d2[at - 1];
      member[at] = member[at - 1];
    }
    d2[at] = d;
    member[at] = i;
  }
};

}  // namespace

int CreaseToCorner(absl::Span<const Vec3d> positions, absl::Span<const Vec3d> normals,
                   const Vec3d& axis, const CornerCreaseOptions& options,
                   absl::Span<Vec3d> cap) {
  const int sectors = std::max(2, options.sectors - options.sectors % 2);
  const int keep = std::max(1, options.per_sector);
  const double max_cosine = std::cos(options.min_angle * kPi / 180.0);
  const Vec3d t1 = Normalized(std::abs(axis[0]) < 0.9 ? Cross(axis, Vec3d{1, 0, 0})
                                                      : Cross(axis, Vec3d{0, 1, 0}));
  const Vec3d t2 = Cross(axis, t1);
  std::vector<Sector> near(static_cast<size_t>(sectors));
  std::vector<Vec3d> centre(sectors), normal(sectors);
  std::vector<char> flat(static_cast<size_t>(sectors));
  int moved = 0;
  for (Vec3d& p : cap) {
    for (Sector& s : near) s.Clear();
    for (size_t i = 0; i < positions.size(); ++i) {
      const Vec3d d = positions[i] - p;
      const double angle = std::atan2(Dot(d, t2), Dot(d, t1));
      const int k = std::min(sectors - 1, static_cast<int>((angle + kPi) / (2 * kPi) * sectors));
      near[k].Add(positions[i], SquaredNorm(d), static_cast<int>(i), keep);
    }
    for (int k = 0; k < sectors; ++k) {
      Vec3d sum{0, 0, 0}, n{0, 0, 0};
      for (int i : near[k].member) {
        sum = sum + positions[i];
        n = n + normals[i];
      }
      if (!near[k].member.empty()) sum = (1.0 / static_cast<double>(near[k].member.size())) * sum;
      centre[k] = sum;
      normal[k] = Normalized(n);
      flat[k] = near[k].count > 0 &&
                Dot((1.0 / near[k].count) * near[k].all - sum, normal[k]) <= options.flat_tolerance;
    }
    double best = 0;
    Vec3d along{0, 0, 0};
    for (int a = 0; a < sectors / 2; ++a) {
      const int b = a + sectors / 2;
      if (near[a].member.empty() || near[b].member.empty() || !flat[a] || !flat[b]) continue;
      const Vec3d& na = normal[a];
      const Vec3d& nb = normal[b];
      if (!(Dot(na, nb) <= max_cosine)) continue;
      const double ha = Dot(p - centre[a], na), hb = Dot(p - centre[b], nb);
      if (!(ha > 0 && hb > 0)) continue;
      // A concave corner: each side lies outside the other's plane (at a convex edge, or
      // round a post, each lies inside).
      if (!(Dot(centre[a] - centre[b], nb) > 0 && Dot(centre[b] - centre[a], na) > 0)) continue;
      // Inward along the normals' mean until the first plane: the union's boundary, by a move
      // that varies continuously with p (the nearer plane's foot jumps across the bisector).
      const Vec3d m = Normalized(na + nb);
      const double ca = Dot(na, m), cb = Dot(nb, m);
      if (!(ca > 0.1 && cb > 0.1)) continue;
      const double t = std::min({ha / ca, hb / cb, options.max_move});
      if (t > best) {
        best = t;
        along = m;
      }
    }
    if (!(best > 0)) continue;
    p = p - best * along;
    ++moved;
  }
  return moved;
}

}  // namespace membrane
