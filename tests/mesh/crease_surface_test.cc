// The fit's crease targets on a whole surface: a box's edges stay sharp where its faces'
// points show them (crease_fit.h, point_fitting.h).
#include <cmath>
#include <iostream>
#include <random>
#include <vector>

#include "core/geometry/point_cloud.h"
#include "core/mesh/smooth_surface.h"
#include "core/mesh/surface_deviation.h"
#include "gtest/gtest.h"
#include "tests/mesh/box_cloud.h"
#include "tests/mesh/cloud_surface.h"
#include "tests/mesh/surface_expectations.h"

namespace membrane {
namespace {

using namespace membrane::testing;

// A rotation that puts no face or edge of the box along the grid's axes.
Vec3d Rotated(const Vec3d& p) {
  const double a = 0.5, b = 0.3;
  const Vec3d q{std::cos(a) * p[0] - std::sin(a) * p[1], std::sin(a) * p[0] + std::cos(a) * p[1],
                p[2]};
  return Vec3d{std::cos(b) * q[0] + std::sin(b) * q[2], q[1],
               -std::sin(b) * q[0] + std::cos(b) * q[2]};
}

struct BoxCase {
  const Vec3d lo{0, 0, 0}, hi{1, 0.8, 0.6};
  PointCloud cloud;
  BoxCase() {
    std::mt19937_64 rng(7);
    cloud = BoxFacePoints(lo, hi, 25000, rng, [](const Vec3d&) { return true; });
    for (Point3f& p : cloud.points) {
      const Vec3d r = Rotated(Vec3d{p[0], p[1], p[2]});
      p = Point3f{static_cast<float>(r[0]), static_cast<float>(r[1]), static_cast<float>(r[2])};
    }
  }
  // Points every `step` along the box's 12 edges, `margin` away from the corners.
  std::vector<Point3f> EdgePoints(double step, double margin) const {
    std::vector<Point3f> out;
    for (int axis = 0; axis < 3; ++axis)
      for (int corner = 0; corner < 4; ++corner) {
        Vec3d a = lo;
        const int u = (axis + 1) % 3, v = (axis + 2) % 3;
        a[u] = corner & 1 ? hi[u] : lo[u];
        a[v] = corner & 2 ? hi[v] : lo[v];
        for (double t = lo[axis] + margin; t <= hi[axis] - margin; t += step) {
          a[axis] = t;
          const Vec3d r = Rotated(a);
          out.push_back(Point3f{static_cast<float>(r[0]), static_cast<float>(r[1]),
                                static_cast<float>(r[2])});
        }
      }
    return out;
  }
};

TEST(CreaseSurface, ABoxsEdgesStaySharp) {
  const BoxCase box;
  SmoothSurfaceOptions creases, quadrics;
  quadrics.fit_options.creases = false;
  const auto sharp = SmoothSurfaceOfCloud(box.cloud, creases);
  const auto round = SmoothSurfaceOfCloud(box.cloud, quadrics);
  ASSERT_TRUE(sharp.ok()) << sharp.status();
  ASSERT_TRUE(round.ok()) << round.status();
  const double l = sharp->voxel_size;
  const std::vector<Point3f> edges = box.EdgePoints(0.25 * l, 3 * l);
  const SurfaceDeviation with = MeasureDeviation(edges, sharp->mesh);
  const SurfaceDeviation without = MeasureDeviation(edges, round->mesh);
  std::cout << "box edges, voxels from the mesh (mean / max): creases " << with.mean / l << " / "
            << with.max / l << ", quadrics alone " << without.mean / l << " / " << without.max / l
            << "; crease targets " << sharp->stats.fit.crease_targets << " (on the line "
            << sharp->stats.fit.crease_line_targets << ")\n";
  EXPECT_LT(with.mean, 0.1 * l);
  EXPECT_LT(with.mean, 0.4 * without.mean);
  EXPECT_EQ(round->stats.fit.crease_targets, 0);
  ExpectValidSurface(sharp->mesh, 1, {0});
  // The faces stay where they were: every point within 0.1 voxel of the mesh on average.
  const SurfaceDeviation points = MeasureDeviation(box.cloud.points, sharp->mesh);
  EXPECT_LT(points.mean, 0.1 * l);
}

}  // namespace
}  // namespace membrane
