#include "core/mesh/point_row_grid.h"

#include <cmath>
#include <random>
#include <vector>

#include "gtest/gtest.h"

namespace membrane {
namespace {

// The points a brute-force scan finds within the radius, against the grid's.
std::vector<int> WithinBrute(const std::vector<Point3f>& points, const Vec3d& c, double r) {
  std::vector<int> out;
  for (size_t i = 0; i < points.size(); ++i) {
    const double dx = points[i][0] - c[0], dy = points[i][1] - c[1], dz = points[i][2] - c[2];
    if (dx * dx + dy * dy + dz * dz <= r * r) out.push_back(static_cast<int>(i));
  }
  return out;
}

TEST(PointRowGrid, FindsExactlyThePointsWithinTheRadius) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> coord(-5, 5);
  std::vector<Point3f> points(3000);
  for (Point3f& p : points) p = {coord(rng), coord(rng), 0.2f * coord(rng)};
  const PointRowGrid grid(points, 0.5);
  std::uniform_real_distribution<double> centre(-7, 7);
  for (int q = 0; q < 300; ++q) {
    const Vec3d c{centre(rng), centre(rng), 0.3 * centre(rng)};
    const double r = 0.1 + (q % 7) * 0.4;
    size_t found = 0;
    grid.ForEachWithin(c, r, [&](const Point3f& p, double d2) {
      EXPECT_LE(d2, r * r);
      const double dx = p[0] - c[0], dy = p[1] - c[1], dz = p[2] - c[2];
      EXPECT_EQ(d2, dx * dx + dy * dy + dz * dz);
      ++found;
    });
    EXPECT_EQ(found, WithinBrute(points, c, r).size()) << "query " << q;
  }
}

TEST(PointRowGrid, PointsOnCellWallsAndOnTheSphereAreFound) {
  // A lattice on the cell walls, queried from lattice points and wall midpoints with radii that
  // put many points exactly on the sphere: the skipped rows and cells must never hold one.
  std::vector<Point3f> points;
  for (int z = -4; z <= 4; ++z)
    for (int y = -4; y <= 4; ++y)
      for (int x = -4; x <= 4; ++x)
        points.push_back({0.25f * x, 0.25f * y, 0.25f * z});
  const PointRowGrid grid(points, 0.25);
  for (const Vec3d& c : {Vec3d{0, 0, 0}, Vec3d{0.125, 0, 0.25}, Vec3d{0.5, -0.25, 0.125}})
    for (double r : {0.25, 0.5, std::sqrt(2 * 0.0625), std::sqrt(3 * 0.0625), 0.75, 1.0}) {
      size_t found = 0;
      grid.ForEachWithin(c, r, [&](const Point3f&, double) { ++found; });
      EXPECT_EQ(found, WithinBrute(points, c, r).size()) << c[0] << " " << c[1] << " " << r;
    }
}

TEST(PointRowGrid, SparseCloudInAHugeBoxStaysSmallAndCorrect) {
  // Two clusters far apart: the cells coarsen instead of covering the gap finely.
  const std::vector<Point3f> points = {
      {0, 0, 0}, {0.1f, 0, 0}, {1e6f, 1e6f, 1e6f}, {1e6f, 1e6f, 1e6f + 0.1f}};
  const PointRowGrid grid(points, 0.01);
  int found = 0;
  grid.ForEachWithin({1e6, 1e6, 1e6}, 0.5, [&](const Point3f&, double) { ++found; });
  EXPECT_EQ(found, 2);
  found = 0;
  grid.ForEachWithin({-5e6, 0, 0}, 1, [&](const Point3f&, double) { ++found; });
  EXPECT_EQ(found, 0);
}

TEST(PointRowGrid, EmptyCloudFindsNothing) {
  const PointRowGrid grid({}, 1.0);
  int found = 0;
  grid.ForEachWithin({0, 0, 0}, 10, [&](const Point3f&, double) { ++found; });
  EXPECT_EQ(found, 0);
}

}  // namespace
}  // namespace membrane
