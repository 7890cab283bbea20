#include "core/mesh/triangle_intersection.h"

#include <cmath>
#include <random>

#include "gtest/gtest.h"

namespace membrane {
namespace {

using I3 = std::array<int64_t, 3>;

I3 Sub(const I3& a, const I3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
I3 CrossI(const I3& a, const I3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
int64_t DotI(const I3& a, const I3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
bool IsZeroI(const I3& a) { return a[0] == 0 && a[1] == 0 && a[2] == 0; }

// Exact reference on small integer coordinates: closed convex sets are disjoint iff some axis
// strictly separates their projections; for two triangles the candidate axes are both normals,
// the 9 edge-edge cross products and the 6 in-plane edge normals (for coplanar pairs).
bool SeparatingAxisIntersect(const std::array<I3, 3>& a, const std::array<I3, 3>& b) {
  const I3 na = CrossI(Sub(a[1], a[0]), Sub(a[2], a[0]));
  const I3 nb = CrossI(Sub(b[1], b[0]), Sub(b[2], b[0]));
  std::vector<I3> axes = {na, nb};
  for (int i = 0; i < 3; ++i) {
    const I3 ea = Sub(a[(i + 1) % 3], a[i]), eb = Sub(b[(i + 1) % 3], b[i]);
    for (int j = 0; j < 3; ++j) axes.push_back(CrossI(ea, Sub(b[(j + 1) % 3], b[j])));
    axes.push_back(CrossI(na, ea));
    axes.push_back(CrossI(nb, eb));
  }
  for (const I3& axis : axes) {
    if (IsZeroI(axis)) continue;
    int64_t amin = INT64_MAX, amax = INT64_MIN, bmin = INT64_MAX, bmax = INT64_MIN;
    for (int i = 0; i < 3; ++i) {
      amin = std::min(amin, DotI(axis, a[i]));
      amax = std::max(amax, DotI(axis, a[i]));
      bmin = std::min(bmin, DotI(axis, b[i]));
      bmax = std::max(bmax, DotI(axis, b[i]));
    }
    if (amax < bmin || bmax < amin) return false;
  }
  return true;
}

Triangle3d ToTriangle(const std::array<I3, 3>& t) {
  Triangle3d out;
  for (int i = 0; i < 3; ++i) out[i] = {double(t[i][0]), double(t[i][1]), double(t[i][2])};
  return out;
}

// Two random triangles with non-zero area and coordinates in [0, 3]: touching, coplanar and
// edge-on-edge cases are frequent.
std::array<std::array<I3, 3>, 2> RandomTrianglePair(std::mt19937& rng) {
  std::uniform_int_distribution<int> coord(0, 3);
  for (;;) {
    std::array<std::array<I3, 3>, 2> pair;
    for (auto& t : pair)
      for (auto& p : t) p = {coord(rng), coord(rng), coord(rng)};
    if (!IsZeroI(CrossI(Sub(pair[0][1], pair[0][0]), Sub(pair[0][2], pair[0][0]))) &&
        !IsZeroI(CrossI(Sub(pair[1][1], pair[1][0]), Sub(pair[1][2], pair[1][0]))))
      return pair;
  }
}

TEST(TriangleIntersection, AgreesWithSeparatingAxesOnSmallIntegerTriangles) {
  std::mt19937 rng(7);
  int hits = 0;
  for (int tested = 0; tested < 200000; ++tested) {
    const auto [a, b] = RandomTrianglePair(rng);
    const bool expected = SeparatingAxisIntersect(a, b);
    hits += expected;
    ASSERT_EQ(TrianglesIntersect(ToTriangle(a), ToTriangle(b)), expected)
        << "a=(" << a[0][0] << a[0][1] << a[0][2] << "," << a[1][0] << a[1][1] << a[1][2] << ","
        << a[2][0] << a[2][1] << a[2][2] << ") b=(" << b[0][0] << b[0][1] << b[0][2] << ","
        << b[1][0] << b[1][1] << b[1][2] << "," << b[2][0] << b[2][1] << b[2][2] << ")";
  }
  EXPECT_GT(hits, 10000);
}

// Small integer triangles placed at `offset` with `step` between integers, in double: the
// coordinates of a quantization grid rather than integers. Touching, coplanar and collinear
// cases stay as frequent, so the filters fail often and the exact arithmetic decides.
struct Lattice {
  double offset, step;
  Triangle3d Place(const std::array<I3, 3>& t) const {
    Triangle3d out;
    for (int i = 0; i < 3; ++i)
      for (int k = 0; k < 3; ++k) out[i][k] = offset + step * static_cast<double>(t[i][k]);
    return out;
  }
};

TEST(TriangleIntersection, IsExactAndOrderFreeOnGridCoordinates) {
  // 128-bit integer path (2.75 + k/64, 1000.5 + k/64) and expansion path (1e6 + k 2^-30, a
  // 50-bit spread per axis); every place is exact in double, so the integer reference holds.
  const Lattice lattices[] = {{2.75, 1.0 / 64}, {1000.5, 1.0 / 64}, {1e6, std::ldexp(1.0, -30)}};
  std::mt19937 rng(11);
  for (const Lattice& lattice : lattices) {
    int hits = 0;
    for (int tested = 0; tested < 40000; ++tested) {
      const auto [a, b] = RandomTrianglePair(rng);
      const bool expected = SeparatingAxisIntersect(a, b);
      hits += expected;
      const Triangle3d ta = lattice.Place(a), tb = lattice.Place(b);
      ASSERT_EQ(TrianglesIntersect(ta, tb), expected) << "offset " << lattice.offset;
      // The same pair listed another way: other first vertices, faces swapped.
      const Triangle3d ra = {ta[1], ta[2], ta[0]}, rb = {tb[2], tb[0], tb[1]};
      ASSERT_EQ(MeshTrianglesIntersect({3, 4, 5}, rb, {0, 1, 2}, ra), expected);
    }
    EXPECT_GT(hits, 2000);
  }
}

TEST(TriangleIntersection, SharedVertexAnswersDoNotDependOnTheOrderOfTheFaces) {
  // Faces around one shared vertex on a grid, as a fitted surface snapped to a file's
  // quantization grid has them: the answer must be the same whichever face and vertex come
  // first (a decoder lists them in another order than the mesh that was checked).
  std::mt19937 rng(13);
  std::uniform_int_distribution<int> coord(-2, 2);
  // A real cloud's grid (not dyadic) around zero, where coordinates span binades and
  // rounded determinants lose their sign.
  const Lattice lattice{-0.0641599968, 0.0263004307};
  int tested = 0, hits = 0;
  while (tested < 40000) {
    std::array<I3, 3> a, b;
    a[0] = b[0] = {0, 0, 0};
    for (int i = 1; i < 3; ++i) {
      a[i] = {coord(rng), coord(rng), coord(rng)};
      b[i] = {coord(rng), coord(rng), coord(rng)};
    }
    if (IsZeroI(CrossI(Sub(a[1], a[0]), Sub(a[2], a[0]))) ||
        IsZeroI(CrossI(Sub(b[1], b[0]), Sub(b[2], b[0]))))
      continue;
    ++tested;
    Triangle3d ta = lattice.Place(a), tb = lattice.Place(b);
    for (Triangle3d* t : {&ta, &tb})  // float32 positions, as a mesh holds
      for (Vec3d& p : *t)
        for (double& x : p) x = static_cast<float>(x);
    const bool first = MeshTrianglesIntersect({0, 1, 2}, ta, {0, 3, 4}, tb);
    hits += first;
    const Triangle3d ra = {ta[2], ta[0], ta[1]}, rb = {tb[1], tb[2], tb[0]};
    ASSERT_EQ(MeshTrianglesIntersect({3, 4, 0}, rb, {2, 0, 1}, ra), first);
    ASSERT_EQ(MeshTrianglesIntersect({0, 3, 4}, tb, {0, 1, 2}, ta), first);
  }
  EXPECT_GT(hits, 1000);
}

TEST(TriangleIntersection, TouchingAtAPointCounts) {
  const Triangle3d a = {Vec3d{0, 0, 0}, Vec3d{1, 0, 0}, Vec3d{0, 1, 0}};
  const Triangle3d b = {Vec3d{1, 0, 0}, Vec3d{2, 0, 1}, Vec3d{2, 1, 1}};
  EXPECT_TRUE(TrianglesIntersect(a, b));
}

TEST(TriangleIntersection, SharedVertexWithoutOverlapIsNotAnIntersection) {
  const Triangle3d a = {Vec3d{0, 0, 0}, Vec3d{1, 0, 0}, Vec3d{0, 1, 0}};
  const Triangle3d b = {Vec3d{0, 0, 0}, Vec3d{-1, 0, 0}, Vec3d{0, -1, 1}};
  EXPECT_FALSE(MeshTrianglesIntersect({0, 1, 2}, a, {0, 3, 4}, b));
}

TEST(TriangleIntersection, CoplanarSharedVertexSectorsOverlap) {
  const Triangle3d a = {Vec3d{0, 0, 0}, Vec3d{2, 0, 0}, Vec3d{0, 2, 0}};
  const Triangle3d b = {Vec3d{0, 0, 0}, Vec3d{1, 1, 0}, Vec3d{-1, 1, 0}};
  EXPECT_TRUE(MeshTrianglesIntersect({0, 1, 2}, a, {0, 3, 4}, b));
}

TEST(TriangleIntersection, SharedEdgeOppositeSidesIsNotAnIntersection) {
  const Triangle3d a = {Vec3d{0, 0, 0}, Vec3d{1, 0, 0}, Vec3d{0, 1, 0}};
  const Triangle3d b = {Vec3d{1, 0, 0}, Vec3d{0, 0, 0}, Vec3d{0, -1, 0}};
  EXPECT_FALSE(MeshTrianglesIntersect({0, 1, 2}, a, {1, 0, 3}, b));
}

}  // namespace
}  // namespace membrane
