#include "core/mesh/triangle_intersection.h"

#include <algorithm>
#include <cmath>

namespace membrane {
namespace {

using Vec2d = std::array<double, 2>;

double Orient2d(const Vec2d& a, const Vec2d& b, const Vec2d& c) {
  return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
}

int Sign(double v) { return (v > 0) - (v < 0); }

// Drops the coordinate along which `normal` is largest: the projection that keeps a planar
// figure least distorted (and non-degenerate when the normal is non-zero).
struct Projector {
  int u = 0, v = 1;
  explicit Projector(const Vec3d& normal) {
    double ax = std::fabs(normal[0]), ay = std::fabs(normal[1]), az = std::fabs(normal[2]);
    if (ax >= ay && ax >= az) {
      u = 1;
      v = 2;
    } else if (ay >= az) {
      u = 2;
      v = 0;
    } else {
      u = 0;
      v = 1;
    }
  }
  Vec2d operator()(const Vec3d& p) const { return {p[u], p[v]}; }
};

bool OnSegment2d(const Vec2d& a, const Vec2d& b, const Vec2d& p) {
  return std::min(a[0], b[0]) <= p[0] && p[0] <= std::max(a[0], b[0]) &&
         std::min(a[1], b[1]) <= p[1] && p[1] <= std::max(a[1], b[1]);
}

// Closed segments [a, b] and [c, d] in the plane share a point.
bool SegmentsIntersect2d(const Vec2d& a, const Vec2d& b, const Vec2d& c, const Vec2d& d) {
  const int o1 = Sign(Orient2d(a, b, c)), o2 = Sign(Orient2d(a, b, d));
  const int o3 = Sign(Orient2d(c, d, a)), o4 = Sign(Orient2d(c, d, b));
  if (o1 * o2 < 0 && o3 * o4 < 0) return true;
  if (o1 == 0 && OnSegment2d(a, b, c)) return true;
  if (o2 == 0 && OnSegment2d(a, b, d)) return true;
  if (o3 == 0 && OnSegment2d(c, d, a)) return true;
  if (o4 == 0 && OnSegment2d(c, d, b)) return true;
  return false;
}

// Closed triangle (a, b, c), non-degenerate, contains p.
bool PointInTriangle2d(const Vec2d& p, const Vec2d& a, const Vec2d& b, const Vec2d& c) {
  const double d1 = Orient2d(a, b, p), d2 = Orient2d(b, c, p), d3 = Orient2d(c, a, p);
  const bool has_neg = d1 < 0 || d2 < 0 || d3 < 0;
  const bool has_pos = d1 > 0 || d2 > 0 || d3 > 0;
  return !(has_neg && has_pos);
}

bool CoplanarSegmentTriangle(const Vec3d& p, const Vec3d& q, const Triangle3d& t,
                             const Vec3d& normal) {
  const Projector proj(normal);
  const Vec2d a = proj(t[0]), b = proj(t[1]), c = proj(t[2]);
  const Vec2d p2 = proj(p), q2 = proj(q);
  return PointInTriangle2d(p2, a, b, c) || SegmentsIntersect2d(p2, q2, a, b) ||
         SegmentsIntersect2d(p2, q2, b, c) || SegmentsIntersect2d(p2, q2, c, a);
}

bool CoplanarTriangles(const Triangle3d& s, const Triangle3d& t, const Vec3d& normal) {
  const Projector proj(normal);
  const Vec2d s0 = proj(s[0]), s1 = proj(s[1]), s2 = proj(s[2]);
  const Vec2d t0 = proj(t[0]), t1 = proj(t[1]), t2 = proj(t[2]);
  const Vec2d se[3][2] = {{s0, s1}, {s1, s2}, {s2, s0}};
  const Vec2d te[3][2] = {{t0, t1}, {t1, t2}, {t2, t0}};
  for (const auto& e : se)
    for (const auto& f : te)
      if (SegmentsIntersect2d(e[0], e[1], f[0], f[1])) return true;
  return PointInTriangle2d(s0, t0, t1, t2) || PointInTriangle2d(t0, s0, s1, s2);
}

// Segment [p, q] against triangle t, given the orientations op, oq of p and q against t's
// plane (not both zero, not strictly of one sign): the line crosses the plane inside the
// segment, so it is enough to know whether the line passes through the closed triangle.
bool CrossingSegmentHitsTriangle(const Vec3d& p, const Vec3d& q, const Triangle3d& t) {
  const int s0 = Sign(Orient3d(p, q, t[0], t[1]));
  const int s1 = Sign(Orient3d(p, q, t[1], t[2]));
  const int s2 = Sign(Orient3d(p, q, t[2], t[0]));
  const bool has_neg = s0 < 0 || s1 < 0 || s2 < 0;
  const bool has_pos = s0 > 0 || s1 > 0 || s2 > 0;
  return !(has_neg && has_pos);
}

bool SegmentTriangleWithOrientations(const Vec3d& p, const Vec3d& q, double op, double oq,
                                     const Triangle3d& t, const Vec3d& normal) {
  if ((op > 0 && oq > 0) || (op < 0 && oq < 0)) return false;
  if (op == 0 && oq == 0) return CoplanarSegmentTriangle(p, q, t, normal);
  return CrossingSegmentHitsTriangle(p, q, t);
}

bool IsZero(const Vec3d& v) { return v[0] == 0 && v[1] == 0 && v[2] == 0; }

}  // namespace

double Orient3d(const Vec3d& a, const Vec3d& b, const Vec3d& c, const Vec3d& d) {
  return Dot(Cross(b - a, c - a), d - a);
}

bool SegmentIntersectsTriangle(const Vec3d& p, const Vec3d& q, const Triangle3d& t) {
  const Vec3d n = TriangleNormal(t[0], t[1], t[2]);
  if (IsZero(n)) return false;
  return SegmentTriangleWithOrientations(p, q, Dot(n, p - t[0]), Dot(n, q - t[0]), t, n);
}

namespace {

bool TrianglesIntersectWithNormals(const Triangle3d& a, const Vec3d& na, const Triangle3d& b,
                                   const Vec3d& nb) {
  if (IsZero(nb) || IsZero(na)) return false;
  double da[3];
  for (int i = 0; i < 3; ++i) da[i] = Dot(nb, a[i] - b[0]);
  if ((da[0] > 0 && da[1] > 0 && da[2] > 0) || (da[0] < 0 && da[1] < 0 && da[2] < 0)) return false;
  double db[3];
  for (int i = 0; i < 3; ++i) db[i] = Dot(na, b[i] - a[0]);
  if ((db[0] > 0 && db[1] > 0 && db[2] > 0) || (db[0] < 0 && db[1] < 0 && db[2] < 0)) return false;
  if (da[0] == 0 && da[1] == 0 && da[2] == 0) return CoplanarTriangles(a, b, nb);
  // Not coplanar: the triangles meet iff an edge of one meets the other (the overlap of the
  // two chords on the planes' common line ends on an edge of one of them).
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3;
    if (SegmentTriangleWithOrientations(a[i], a[j], da[i], da[j], b, nb)) return true;
    if (SegmentTriangleWithOrientations(b[i], b[j], db[i], db[j], a, na)) return true;
  }
  return false;
}

}  // namespace

bool TrianglesIntersect(const Triangle3d& a, const Triangle3d& b) {
  return TrianglesIntersectWithNormals(a, TriangleNormal(a[0], a[1], a[2]), b,
                                       TriangleNormal(b[0], b[1], b[2]));
}

bool MeshTrianglesIntersect(const std::array<int32_t, 3>& ia, const Triangle3d& a,
                            const std::array<int32_t, 3>& ib, const Triangle3d& b) {
  return MeshTrianglesIntersect(ia, a, TriangleNormal(a[0], a[1], a[2]), ib, b,
                                TriangleNormal(b[0], b[1], b[2]));
}

bool MeshTrianglesIntersect(const std::array<int32_t, 3>& ia, const Triangle3d& a, const Vec3d& na,
                            const std::array<int32_t, 3>& ib, const Triangle3d& b,
                            const Vec3d& nb) {
  int shared = 0, sa = -1, sb = -1;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (ia[i] == ib[j]) {
        ++shared;
        sa = i;
        sb = j;
      }
  if (shared == 0) return TrianglesIntersectWithNormals(a, na, b, nb);
  if (shared == 3) return true;
  if (IsZero(na) || IsZero(nb)) return false;
  if (shared == 1) {
    // Non-coplanar faces through a common vertex meet along one ray from it; they overlap
    // beyond the vertex iff the shorter chord ends on the other face, i.e. iff an opposite
    // edge meets the other face. The same holds for coplanar sectors.
    // Fast exit, the common case on a smooth surface: b's other two vertices strictly on one
    // side of a's plane, so b meets that plane only at the shared vertex (or vice versa).
    const Vec3d& v = a[sa];
    const double b1 = Dot(na, b[(sb + 1) % 3] - v), b2 = Dot(na, b[(sb + 2) % 3] - v);
    if ((b1 > 0 && b2 > 0) || (b1 < 0 && b2 < 0)) return false;
    const double a1 = Dot(nb, a[(sa + 1) % 3] - v), a2 = Dot(nb, a[(sa + 2) % 3] - v);
    if ((a1 > 0 && a2 > 0) || (a1 < 0 && a2 < 0)) return false;
    return SegmentIntersectsTriangle(a[(sa + 1) % 3], a[(sa + 2) % 3], b) ||
           SegmentIntersectsTriangle(b[(sb + 1) % 3], b[(sb + 2) % 3], a);
  }
  // Shared edge: the faces overlap only when coplanar and folded (apexes on one side).
  int apex_a = 0, apex_b = 0;
  for (int i = 0; i < 3; ++i) {
    if (ia[i] != ib[0] && ia[i] != ib[1] && ia[i] != ib[2]) apex_a = i;
    if (ib[i] != ia[0] && ib[i] != ia[1] && ib[i] != ia[2]) apex_b = i;
  }
  if (Dot(na, b[apex_b] - a[apex_a]) != 0) return false;
  const Vec3d& u = a[(apex_a + 1) % 3];
  const Vec3d& w = a[(apex_a + 2) % 3];
  return Dot(Cross(w - u, a[apex_a] - u), Cross(w - u, b[apex_b] - u)) > 0;
}

}  // namespace membrane
