#include "core/mesh/triangle_intersection.h"

#include <algorithm>
#include <bit>
#include <climits>
#include <cmath>
#include <cstdint>
#include <optional>
#include <utility>

namespace membrane {
namespace {

using Vec2d = std::array<double, 2>;

// Shewchuk's error bounds for the first stage of his orient2d and orient3d ("Adaptive
// Precision Floating-Point Arithmetic and Fast Robust Geometric Predicates", 1997): when the
// determinant computed in double exceeds bound * permanent its sign is the exact sign. Every
// sign below is exact, so every answer depends on the positions alone, not on the order of the
// vertices in a face or of the faces in a mesh.
constexpr double kEpsilon = 1.1102230246251565e-16;  // 2^-53
constexpr double kOrient2dBound = (3.0 + 16.0 * kEpsilon) * kEpsilon;
constexpr double kOrient3dBound = (7.0 + 56.0 * kEpsilon) * kEpsilon;

int Sign(double v) { return (v > 0) - (v < 0); }

// det[a - c, b - c]: positive when (a, b, c) turn counterclockwise.
double Det2(const Vec2d& a, const Vec2d& b, const Vec2d& c, double* permanent) {
  const double left = (a[0] - c[0]) * (b[1] - c[1]);
  const double right = (a[1] - c[1]) * (b[0] - c[0]);
  *permanent = std::fabs(left) + std::fabs(right);
  return left - right;
}

// det[a - d, b - d, c - d]: negative when d is on the side (b - a) x (c - a) points to.
double Det3(const Vec3d& a, const Vec3d& b, const Vec3d& c, const Vec3d& d, double* permanent) {
  const double adx = a[0] - d[0], ady = a[1] - d[1], adz = a[2] - d[2];
  const double bdx = b[0] - d[0], bdy = b[1] - d[1], bdz = b[2] - d[2];
  const double cdx = c[0] - d[0], cdy = c[1] - d[1], cdz = c[2] - d[2];
  const double bc = bdx * cdy - bdy * cdx, ca = cdx * ady - cdy * adx, ab = adx * bdy - ady * bdx;
  *permanent = (std::fabs(bdx * cdy) + std::fabs(bdy * cdx)) * std::fabs(adz) +
               (std::fabs(cdx * ady) + std::fabs(cdy * adx)) * std::fabs(bdz) +
               (std::fabs(adx * bdy) + std::fabs(ady * bdx)) * std::fabs(cdz);
  return adz * bc + bdz * ca + cdz * ab;
}

// Exact arithmetic on expansions (Shewchuk, same paper): a number held as a sum of doubles
// of increasing magnitude that do not overlap. Used only where the filters above cannot decide,
// that is on (nearly) degenerate configurations, which grids make common.
class Expansion {
 public:
  void Add(double b) {
    int n = 0;
    double q = b;
    for (int i = 0; i < size_; ++i) {
      double sum, err;
      TwoSum(q, terms_[i], sum, err);
      q = sum;
      if (err != 0) terms_[n++] = err;
    }
    if (q != 0 || n == 0) terms_[n++] = q;
    size_ = n;
  }
  // Adds sign * x * y * z exactly.
  void AddProduct(double sign, double x, double y, double z) {
    double p1, p0, q1, q0, r1, r0;
    TwoProduct(x, y, p1, p0);
    TwoProduct(p1, z, q1, q0);
    TwoProduct(p0, z, r1, r0);
    Add(sign * r0);
    Add(sign * q0);
    Add(sign * r1);
    Add(sign * q1);
  }
  void AddProduct(double sign, double x, double y) {
    double p1, p0;
    TwoProduct(x, y, p1, p0);
    Add(sign * p0);
    Add(sign * p1);
  }
  int Sign() const { return size_ == 0 ? 0 : (terms_[size_ - 1] > 0) - (terms_[size_ - 1] < 0); }

 private:
  static void TwoSum(double a, double b, double& x, double& y) {
    x = a + b;
    const double bv = x - a, av = x - bv;
    y = (a - av) + (b - bv);
  }
  // Dekker's product: std::fma is a library call on the baseline x86-64 this builds for.
  static void Split(double a, double& hi, double& lo) {
    const double c = 134217729.0 * a;  // 2^27 + 1
    hi = c - (c - a);
    lo = a - hi;
  }
  static void TwoProduct(double a, double b, double& x, double& y) {
    x = a * b;
    double ahi, alo, bhi, blo;
    Split(a, ahi, alo);
    Split(b, bhi, blo);
    y = alo * blo - (((x - ahi * bhi) - alo * bhi) - ahi * blo);
  }
  // At most one term per Add, and at most 4 * 24 Adds.
  std::array<double, 100> terms_{};
  int size_ = 0;
};

// d = a - b in double; true when that is exact (the error term of Shewchuk's Two-Diff is 0).
bool ExactDifference(double a, double b, double& d) {
  d = a - b;
  const double b_virtual = a - d;
  const double a_virtual = d + b_virtual;
  return (a - a_virtual) + (b_virtual - b) == 0;
}

// The exact sign of det[a - c, b - c].
int ExactDet2Sign(const Vec2d& a, const Vec2d& b, const Vec2d& c) {
  double acx, acy, bcx, bcy;
  Expansion e;
  if (ExactDifference(a[0], c[0], acx) && ExactDifference(a[1], c[1], acy) &&
      ExactDifference(b[0], c[0], bcx) && ExactDifference(b[1], c[1], bcy)) {
    e.AddProduct(1, acx, bcy);
    e.AddProduct(-1, acy, bcx);
  } else {  // det [[ax ay 1] [bx by 1] [cx cy 1]]
    e.AddProduct(1, a[0], b[1]);
    e.AddProduct(-1, a[1], b[0]);
    e.AddProduct(-1, a[0], c[1]);
    e.AddProduct(1, a[1], c[0]);
    e.AddProduct(1, b[0], c[1]);
    e.AddProduct(-1, b[1], c[0]);
  }
  return e.Sign();
}

// v as an odd integer times a power of two (m = 0 for v = 0), from its bits.
struct Dyadic {
  int64_t m = 0;
  int e = 0;
};
Dyadic Decompose(double v) {
  const uint64_t bits = std::bit_cast<uint64_t>(v);
  const int field = static_cast<int>((bits >> 52) & 0x7ff);
  uint64_t mantissa = bits & ((uint64_t{1} << 52) - 1);
  if (field != 0) mantissa |= uint64_t{1} << 52;
  if (mantissa == 0) return {};
  const int zeros = std::countr_zero(mantissa);
  Dyadic d;
  d.m = static_cast<int64_t>(mantissa >> zeros);
  if (bits >> 63) d.m = -d.m;
  d.e = (field == 0 ? -1074 : field - 1075) + zeros;
  return d;
}

// The exact sign of det[a - d, b - d, c - d] in 128-bit integers, when every coordinate of
// an axis is a multiple of that axis's smallest power of two with at most 40 bits (the case of
// float32 positions in a mesh of similar magnitudes): each axis scaled by a power of two, the
// determinant's terms are products of three 41-bit differences. nullopt otherwise.
std::optional<int> IntegerDet3Sign(const Vec3d& a, const Vec3d& b, const Vec3d& c,
                                   const Vec3d& d) {
  const Vec3d* points[4] = {&a, &b, &c, &d};
  __int128 r[3][3];
  for (int k = 0; k < 3; ++k) {
    Dyadic v[4];
    int low = INT32_MAX;
    for (int i = 0; i < 4; ++i) {
      v[i] = Decompose((*points[i])[k]);
      if (v[i].m != 0) low = std::min(low, v[i].e);
    }
    __int128 value[4];
    for (int i = 0; i < 4; ++i) {
      if (v[i].m == 0) {
        value[i] = 0;
        continue;
      }
      const int shift = v[i].e - low;
      const uint64_t magnitude = static_cast<uint64_t>(v[i].m < 0 ? -v[i].m : v[i].m);
      if (shift > 40 || std::bit_width(magnitude) + shift > 40) return std::nullopt;
      value[i] = static_cast<__int128>(v[i].m) << shift;
    }
    for (int i = 0; i < 3; ++i) r[i][k] = value[i] - value[3];
  }
  const __int128 det = r[0][0] * (r[1][1] * r[2][2] - r[1][2] * r[2][1]) -
                       r[0][1] * (r[1][0] * r[2][2] - r[1][2] * r[2][0]) +
                       r[0][2] * (r[1][0] * r[2][1] - r[1][1] * r[2][0]);
  return (det > 0) - (det < 0);
}

int Orient2dSign(const Vec2d& a, const Vec2d& b, const Vec2d& c);

// The exact sign of det[a - d, b - d, c - d].
int ExactDet3Sign(const Vec3d& a, const Vec3d& b, const Vec3d& c, const Vec3d& d) {
  // Four points on a plane parallel to an axis (their projections along it collinear) give
  // zero: the common undecided case on a grid (faces of a flat part of a surface that is
  // parallel to an axis, as CAD parts often are), and cheaper to see than to compute.
  const Vec3d* points[4] = {&a, &b, &c, &d};
  for (int axis = 0; axis < 3; ++axis) {
    const int u = (axis + 1) % 3, w = (axis + 2) % 3;
    Vec2d q[4];
    for (int i = 0; i < 4; ++i) q[i] = {(*points[i])[u], (*points[i])[w]};
    int other = 1;
    while (other < 4 && q[other] == q[0]) ++other;
    bool collinear = true;
    for (int i = other + 1; i < 4 && collinear; ++i)
      collinear = Orient2dSign(q[0], q[other], q[i]) == 0;
    if (collinear) return 0;
  }
  if (const std::optional<int> sign = IntegerDet3Sign(a, b, c, d)) return *sign;
  std::array<Vec3d, 3> r;
  bool exact = true;
  const Vec3d* rows[3] = {&a, &b, &c};
  for (int i = 0; i < 3 && exact; ++i)
    for (int k = 0; k < 3 && exact; ++k) exact = ExactDifference((*rows[i])[k], d[k], r[i][k]);
  Expansion e;
  // det[x; y; z] of three rows, times sign, into e.
  auto add_det = [&e](double sign, const Vec3d& x, const Vec3d& y, const Vec3d& z) {
    e.AddProduct(sign, x[0], y[1], z[2]);
    e.AddProduct(-sign, x[0], y[2], z[1]);
    e.AddProduct(-sign, x[1], y[0], z[2]);
    e.AddProduct(sign, x[1], y[2], z[0]);
    e.AddProduct(sign, x[2], y[0], z[1]);
    e.AddProduct(-sign, x[2], y[1], z[0]);
  };
  if (exact) {
    add_det(1, r[0], r[1], r[2]);
  } else {  // det [[a 1] [b 1] [c 1] [d 1]], along the column of ones
    add_det(-1, b, c, d);
    add_det(1, a, c, d);
    add_det(-1, a, b, d);
    add_det(1, a, b, c);
  }
  return e.Sign();
}

// The sign of (b - a) x (c - a) in the plane: the filter's when it decides, else exact.
int Orient2dSign(const Vec2d& a, const Vec2d& b, const Vec2d& c) {
  double permanent;
  const double det = Det2(a, b, c, &permanent);
  if (std::fabs(det) > kOrient2dBound * permanent) return Sign(det);
  // Every product has an exactly zero factor (a zero difference is exact): the determinant is
  // exactly zero. Axis-aligned degenerate cases, the common ones on grids, end here.
  if (permanent == 0) return 0;
  // Two equal points: exactly zero too (segments ending at a shared vertex ask this often).
  if (a == b || b == c || a == c) return 0;
  return ExactDet2Sign(a, b, c);
}

// The sign of ((b - a) x (c - a)) . (d - a): which side of plane (a, b, c) d lies on; the
// filter's when it decides, else exact.
int Orient3dSign(const Vec3d& a, const Vec3d& b, const Vec3d& c, const Vec3d& d) {
  double permanent;
  const double det = Det3(a, b, c, d, &permanent);
  if (std::fabs(det) > kOrient3dBound * permanent) return -Sign(det);
  if (permanent == 0) return 0;  // as in Orient2dSign
  if (a == b || a == c || a == d || b == c || b == d || c == d) return 0;
  return -ExactDet3Sign(a, b, c, d);
}

// Which side of face t's plane p lies on, as Orient3dSign(t[0], t[1], t[2], p), with the
// filter on the face's precomputed plane: the same cofactor expansion as Det3's (along the
// point's row), so the same bound holds; taken a little wider.
constexpr double kPlaneSideBound = (8.0 + 64.0 * kEpsilon) * kEpsilon;
int PlaneSide(const FacePlane& plane, const Triangle3d& t, const Vec3d& p) {
  const Vec3d w = p - plane.base;
  const double det = Dot(plane.normal, w);
  const double permanent = plane.bound[0] * std::fabs(w[0]) + plane.bound[1] * std::fabs(w[1]) +
                           plane.bound[2] * std::fabs(w[2]);
  if (std::fabs(det) > kPlaneSideBound * permanent) return Sign(det);
  if (permanent == 0) return 0;  // every product has an exactly zero factor
  // Undecided here means Orient3dSign's own filter would fail too: straight to exact.
  if (p == t[0] || p == t[1] || p == t[2] || t[0] == t[1] || t[1] == t[2] || t[0] == t[2])
    return 0;
  return -ExactDet3Sign(t[0], t[1], t[2], p);
}

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

// The projection for two coplanar faces, the same whichever comes first.
Projector PairProjector(const Vec3d& na, const Vec3d& nb) {
  return Projector({std::fabs(na[0]) + std::fabs(nb[0]), std::fabs(na[1]) + std::fabs(nb[1]),
                    std::fabs(na[2]) + std::fabs(nb[2])});
}

// True when the line of an edge of convex polygon `poly` (n = 3: a triangle, its third vertex
// gives the inside; n = 2: a segment, either side) has all m points of `other` strictly
// outside. Two closed convex figures in the plane are disjoint iff some edge line of one
// separates them so (separating axes: the edges' normals): with exact signs, exact.
bool EdgeSeparates(const Vec2d* poly, int n, const Vec2d* other, int m) {
  for (int i = 0; i < (n == 3 ? 3 : 1); ++i) {
    const Vec2d& e0 = poly[i];
    const Vec2d& e1 = poly[(i + 1) % n];
    // A segment has no inside: all of `other` on either side separates.
    const int inside = n == 3 ? Orient2dSign(e0, e1, poly[(i + 2) % 3]) : 0;
    if (n == 3 && inside == 0) continue;
    if (n == 2 && e0 == e1) continue;
    int first = 0;
    bool separated = true;
    for (int j = 0; j < m && separated; ++j) {
      const int side = Orient2dSign(e0, e1, other[j]);
      if (n == 3) {
        separated = side * inside < 0;
      } else {
        if (j == 0) first = side;
        separated = side != 0 && side == first;
      }
    }
    if (separated) return true;
  }
  return false;
}

bool CoplanarSegmentTriangle(const Vec3d& p, const Vec3d& q, const Triangle3d& t,
                             const Projector& proj) {
  const Vec2d tri[3] = {proj(t[0]), proj(t[1]), proj(t[2])};
  const Vec2d seg[2] = {proj(p), proj(q)};
  return !EdgeSeparates(tri, 3, seg, 2) && !EdgeSeparates(seg, 2, tri, 3);
}

bool CoplanarTriangles(const Triangle3d& s, const Triangle3d& t, const Projector& proj) {
  const Vec2d a[3] = {proj(s[0]), proj(s[1]), proj(s[2])};
  const Vec2d b[3] = {proj(t[0]), proj(t[1]), proj(t[2])};
  return !EdgeSeparates(a, 3, b, 3) && !EdgeSeparates(b, 3, a, 3);
}

// Segment [p, q] against triangle t, given the sides op, oq of p and q of t's plane (not both
// zero, not of one strict sign): the line crosses the plane inside the segment, so it is
// enough to know whether the line passes through the closed triangle.
bool CrossingSegmentHitsTriangle(const Vec3d& p, const Vec3d& q, const Triangle3d& t) {
  const int s0 = Orient3dSign(p, q, t[0], t[1]);
  const int s1 = Orient3dSign(p, q, t[1], t[2]);
  const int s2 = Orient3dSign(p, q, t[2], t[0]);
  const bool has_neg = s0 < 0 || s1 < 0 || s2 < 0;
  const bool has_pos = s0 > 0 || s1 > 0 || s2 > 0;
  return !(has_neg && has_pos);
}

bool SegmentTriangleWithSides(const Vec3d& p, const Vec3d& q, int op, int oq,
                              const Triangle3d& t, const FacePlane& plane) {
  if (op * oq > 0) return false;
  if (op == 0 && oq == 0) return CoplanarSegmentTriangle(p, q, t, Projector(plane.normal));
  return CrossingSegmentHitsTriangle(p, q, t);
}

// Coplanar faces (v, a1, a2) and (v, b1, b2) with a common vertex v meet beyond it iff their
// angles at v share a ray, i.e. iff one angle (closed, under 180 degrees) holds an edge ray of
// the other: 8 orientations instead of the general coplanar test's 30 or so (fitted surfaces
// on a quantization grid have many exactly coplanar neighbours).
bool CoplanarSectorsOverlap(const Vec3d& v, const Vec3d& a1, const Vec3d& a2, const Vec3d& b1,
                            const Vec3d& b2, const Projector& proj) {
  const Vec2d o = proj(v);
  Vec2d p1 = proj(a1), p2 = proj(a2), q1 = proj(b1), q2 = proj(b2);
  if (Orient2dSign(o, p1, p2) < 0) std::swap(p1, p2);
  if (Orient2dSign(o, q1, q2) < 0) std::swap(q1, q2);
  // Ray o->r lies in the closed angle from o->lo counterclockwise to o->hi.
  auto in_angle = [&o](const Vec2d& lo, const Vec2d& hi, const Vec2d& r) {
    return Orient2dSign(o, lo, r) >= 0 && Orient2dSign(o, r, hi) >= 0;
  };
  return in_angle(p1, p2, q1) || in_angle(p1, p2, q2) || in_angle(q1, q2, p1) ||
         in_angle(q1, q2, p2);
}

bool IsZero(const Vec3d& v) { return v[0] == 0 && v[1] == 0 && v[2] == 0; }

bool TrianglesIntersectWithPlanes(const Triangle3d& a, const FacePlane& pa, const Triangle3d& b,
                                  const FacePlane& pb) {
  if (IsZero(pb.normal) || IsZero(pa.normal)) return false;
  int da[3];
  for (int i = 0; i < 3; ++i) da[i] = PlaneSide(pb, b, a[i]);
  if ((da[0] > 0 && da[1] > 0 && da[2] > 0) || (da[0] < 0 && da[1] < 0 && da[2] < 0)) return false;
  int db[3];
  for (int i = 0; i < 3; ++i) db[i] = PlaneSide(pa, a, b[i]);
  if ((db[0] > 0 && db[1] > 0 && db[2] > 0) || (db[0] < 0 && db[1] < 0 && db[2] < 0)) return false;
  if (da[0] == 0 && da[1] == 0 && da[2] == 0)
    return CoplanarTriangles(a, b, PairProjector(pa.normal, pb.normal));
  // Not coplanar: the triangles meet iff an edge of one meets the other (the overlap of the
  // two chords on the planes' common line ends on an edge of one of them).
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3;
    if (SegmentTriangleWithSides(a[i], a[j], da[i], da[j], b, pb)) return true;
    if (SegmentTriangleWithSides(b[i], b[j], db[i], db[j], a, pa)) return true;
  }
  return false;
}

}  // namespace

FacePlane MakeFacePlane(const Triangle3d& t) {
  std::array<const Vec3d*, 3> p{&t[0], &t[1], &t[2]};
  double parity = 1;
  for (int i = 1; i < 3; ++i)
    for (int j = i; j > 0 && *p[j] < *p[j - 1]; --j) {
      std::swap(p[j], p[j - 1]);
      parity = -parity;
    }
  FacePlane plane;
  plane.base = *p[0];
  const Vec3d e1 = *p[1] - *p[0], e2 = *p[2] - *p[0];
  plane.normal = parity * Cross(e1, e2);
  plane.bound = {std::fabs(e1[1] * e2[2]) + std::fabs(e1[2] * e2[1]),
                 std::fabs(e1[2] * e2[0]) + std::fabs(e1[0] * e2[2]),
                 std::fabs(e1[0] * e2[1]) + std::fabs(e1[1] * e2[0])};
  return plane;
}

Vec3d CanonicalNormal(const Triangle3d& t) { return MakeFacePlane(t).normal; }

bool TrianglesIntersect(const Triangle3d& a, const Triangle3d& b) {
  return TrianglesIntersectWithPlanes(a, MakeFacePlane(a), b, MakeFacePlane(b));
}

bool MeshTrianglesIntersect(const std::array<int32_t, 3>& ia, const Triangle3d& a,
                            const std::array<int32_t, 3>& ib, const Triangle3d& b) {
  return MeshTrianglesIntersect(ia, a, MakeFacePlane(a), ib, b, MakeFacePlane(b));
}

bool MeshTrianglesIntersect(const std::array<int32_t, 3>& ia, const Triangle3d& a,
                            const FacePlane& pa, const std::array<int32_t, 3>& ib,
                            const Triangle3d& b, const FacePlane& pb) {
  int shared = 0, sa = -1, sb = -1;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (ia[i] == ib[j]) {
        ++shared;
        sa = i;
        sb = j;
      }
  if (shared == 0) return TrianglesIntersectWithPlanes(a, pa, b, pb);
  if (shared == 3) return true;
  if (IsZero(pa.normal) || IsZero(pb.normal)) return false;
  if (shared == 1) {
    // Non-coplanar faces through a common vertex meet along one ray from it; they overlap
    // beyond the vertex iff the shorter chord ends on the other face, i.e. iff an opposite
    // edge meets the other face. The same holds for coplanar sectors.
    // Fast exit, the common case on a smooth surface: b's other two vertices strictly on one
    // side of a's plane, so b meets that plane only at the shared vertex (or vice versa).
    const Vec3d& v = a[sa];
    const Vec3d &b1 = b[(sb + 1) % 3], &b2 = b[(sb + 2) % 3];
    const int s1 = PlaneSide(pa, a, b1), s2 = PlaneSide(pa, a, b2);
    if (s1 * s2 > 0) return false;
    const Vec3d &a1 = a[(sa + 1) % 3], &a2 = a[(sa + 2) % 3];
    const int t1 = PlaneSide(pb, b, a1), t2 = PlaneSide(pb, b, a2);
    if (t1 * t2 > 0) return false;
    if (s1 == 0 && s2 == 0 && t1 == 0 && t2 == 0) {
      return CoplanarSectorsOverlap(v, a1, a2, b1, b2, PairProjector(pa.normal, pb.normal));
    }
    return SegmentTriangleWithSides(a1, a2, t1, t2, b, pb) ||
           SegmentTriangleWithSides(b1, b2, s1, s2, a, pa);
  }
  // Shared edge: the faces overlap only when coplanar and folded (apexes on one side).
  int apex_a = 0, apex_b = 0;
  for (int i = 0; i < 3; ++i) {
    if (ia[i] != ib[0] && ia[i] != ib[1] && ia[i] != ib[2]) apex_a = i;
    if (ib[i] != ia[0] && ib[i] != ia[1] && ib[i] != ia[2]) apex_b = i;
  }
  if (PlaneSide(pa, a, b[apex_b]) != 0) return false;
  // Coplanar: folded when both apexes lie strictly on one side of the shared edge's line.
  const Projector proj = PairProjector(pa.normal, pb.normal);
  const Vec2d u = proj(a[(apex_a + 1) % 3]), w = proj(a[(apex_a + 2) % 3]);
  const int side_a = Orient2dSign(u, w, proj(a[apex_a]));
  const int side_b = Orient2dSign(u, w, proj(b[apex_b]));
  return side_a != 0 && side_a == side_b;
}

}  // namespace membrane
