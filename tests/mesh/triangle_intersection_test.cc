#include "core/mesh/triangle_intersection.h"

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

TEST(TriangleIntersection, AgreesWithSeparatingAxesOnSmallIntegerTriangles) {
  // Coordinates in [0, 3]: touching, coplanar and edge-on-edge cases are frequent.
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> coord(0, 3);
  int tested = 0, hits = 0;
  while (tested < 200000) {
    std::array<I3, 3> a, b;
    for (auto& p : a) p = {coord(rng), coord(rng), coord(rng)};
    for (auto& p : b) p = {coord(rng), coord(rng), coord(rng)};
    if (IsZeroI(CrossI(Sub(a[1], a[0]), Sub(a[2], a[0]))) ||
        IsZeroI(CrossI(Sub(b[1], b[0]), Sub(b[2], b[0]))))
      continue;
    ++tested;
    const bool expected = SeparatingAxisIntersect(a, b);
    hits += expected;
    ASSERT_EQ(TrianglesIntersect(ToTriangle(a), ToTriangle(b)), expected)
        << "a=(" << a[0][0] << a[0][1] << a[0][2] << "," << a[1][0] << a[1][1] << a[1][2] << ","
        << a[2][0] << a[2][1] << a[2][2] << ") b=(" << b[0][0] << b[0][1] << b[0][2] << ","
        << b[1][0] << b[1][1] << b[1][2] << "," << b[2][0] << b[2][1] << b[2][2] << ")";
  }
  EXPECT_GT(hits, 10000);
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
