// The caps' thin plate read from the rim (core/mesh/hole_caps.h, wrap_rms): a hole that
// swallows the edge of a thin slab is spanned along the slab's faces, and the unscanned flat
// base of a frustum, whose rim is no height field either, stays flat, also where a point seen
// inside it holds the cap.
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <random>

#include "core/mesh/hole_caps.h"
#include "core/mesh/mesh_check.h"
#include "core/mesh/smooth_surface.h"
#include "gtest/gtest.h"
#include "tests/mesh/box_cloud.h"
#include "tests/mesh/cloud_surface.h"
#include "tests/mesh/surface_expectations.h"

namespace membrane {
namespace {

constexpr double kVoxel = 0.05;

using CapResult = testing::CapMeasure;

CapResult Reconstruct(const PointCloud& cloud, double wrap_rms,
                      const std::function<bool(const Vec3d&)>& in_hole,
                      const std::function<double(const Vec3d&)>& error) {
  SmoothSurfaceOptions options;
  options.hole_caps.wrap_rms = wrap_rms;
  return testing::MeasureCap(cloud, options, kVoxel, in_hole, error);
}

// A slab |x| <= 2, |y| <= 0.25, -2 <= z <= 1 (10 voxels thick), sampled uniformly, but no
// point within 1.25 of (0, 0.25, 1), a point of the edge between its top face and its face
// z = 1: the hole swallows that edge, its rim runs over the top face and the bottom face.
constexpr double kHalfThick = 0.25;
const Vec3d kSlabHole{0, kHalfThick, 1};
constexpr double kSlabHoleRadius = 1.25;

PointCloud SlabWithHole(int per_unit_area) {
  std::mt19937_64 rng(5);
  return testing::BoxFacePoints(
      Vec3d{-2, -kHalfThick, -2}, Vec3d{2, kHalfThick, 1}, per_unit_area, rng,
      [](const Vec3d& p) {
        return SquaredNorm(p - kSlabHole) >= kSlabHoleRadius * kSlabHoleRadius;
      });
}

// Distance to the slab's surface (the box's boundary).
double SlabDistance(const Vec3d& p) {
  const Vec3d half{2, kHalfThick, 1.5};
  const Vec3d centre{0, 0, -0.5};
  double outside = 0, inside = std::numeric_limits<double>::max();
  for (int k = 0; k < 3; ++k) {
    const double d = std::abs(p[k] - centre[k]) - half[k];
    outside += d > 0 ? d * d : 0;
    inside = std::min(inside, -d);
  }
  return outside > 0 ? std::sqrt(outside) : inside;
}

TEST(HoleCapRims, HoleOverTheEdgeOfAThinPartIsSpannedAlongItsFaces) {
  const PointCloud cloud = SlabWithHole(3000);
  auto in_hole = [](const Vec3d& v) {
    return SquaredNorm(v - kSlabHole) < 0.8 * kSlabHoleRadius * kSlabHoleRadius * 0.8;
  };
  const double never = std::numeric_limits<double>::infinity();
  const CapResult wrapped = Reconstruct(cloud, HoleCapOptions{}.wrap_rms, in_hole, SlabDistance);
  const CapResult blended = Reconstruct(cloud, never, in_hole, SlabDistance);
  // The rim runs over both faces, 10 voxels apart: no height field, and far off its plane.
  EXPECT_EQ(wrapped.caps.wrapped, 1);
  EXPECT_EQ(blended.caps.wrapped, 0);
  EXPECT_EQ(wrapped.caps.harmonic_starts, 1);
  ASSERT_GT(wrapped.vertices, 100);
  std::printf("slab edge: mean / max distance to the slab, voxels: converged %.2f / %.2f, "
              "60 iterations from the harmonic map %.2f / %.2f\n",
              wrapped.mean_error, wrapped.max_error, blended.mean_error, blended.max_error);
  // Measured: 0.81 / 3.02 voxels converged and swept on along the slab's faces (1.44 / 3.86
  // converged alone), 2.70 / 4.99 with 60 iterations from the harmonic map (it cuts across the
  // edge); the largest distances lie at the slab's sharp corners, which no smooth cap follows.
  EXPECT_LT(wrapped.mean_error, 2.0);
  EXPECT_LT(wrapped.max_error, 5.0);
  EXPECT_GT(blended.mean_error, wrapped.mean_error + 0.8);
  testing::ExpectValidReport(wrapped.check, 1, {0});
  testing::ExpectValidReport(blended.check, 1, {0});
}

// A frustum standing on its base (radius 1.5 at y = 0, 0.6 at y = 1.5), scanned everywhere but
// on the base: the rim's band runs up the walls, whose normals lean 31 degrees away from the
// base's outward normal (no height field), within a few voxels of the base's plane.
constexpr double kBottom = 1.5, kTop = 0.6, kHeight = 1.5;

PointCloud Frustum(int per_unit_area, bool base) {
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> u(0, 1);
  PointCloud cloud;
  const double slant = std::hypot(kBottom - kTop, kHeight);
  const int wall = static_cast<int>(per_unit_area * M_PI * (kBottom + kTop) * slant);
  for (int i = 0; i < wall;) {
    const double h = kHeight * u(rng);
    const double r = kBottom - (kBottom - kTop) * h / kHeight;
    if (u(rng) * kBottom > r) continue;  // area-uniform: density along h grows with r
    const double a = 2 * M_PI * u(rng);
    cloud.points.push_back(ToPoint3f(Vec3d{r * std::cos(a), h, r * std::sin(a)}));
    ++i;
  }
  for (const auto& [radius, y] : {std::pair{kTop, kHeight}, std::pair{kBottom, 0.0}}) {
    if (y == 0.0 && !base) continue;
    const int n = static_cast<int>(per_unit_area * M_PI * radius * radius);
    for (int i = 0; i < n; ++i) {
      const double r = radius * std::sqrt(u(rng)), a = 2 * M_PI * u(rng);
      cloud.points.push_back(ToPoint3f(Vec3d{r * std::cos(a), y, r * std::sin(a)}));
    }
  }
  return cloud;
}

// The membrane of a solid open at its base enters it and hollows it (a wall around a cave,
// no cap to shape): the caps are given the surface nets of the closed frustum and the cloud
// without its base, whose vertices then lie in a gap under a rim that is no height field.
TEST(HoleCapRims, OpenFlatBaseStaysFlat) {
  SmoothSurfaceOptions surface;
  surface.fit = false;  // the surface nets, uncapped
  absl::StatusOr<testing::CloudSurface> closed =
      testing::SmoothSurfaceOfCloud(Frustum(3000, true), surface, kVoxel);
  ASSERT_TRUE(closed.ok()) << closed.status();
  const TriangleMesh* nets = &closed->mesh;
  const PointCloud open = Frustum(3000, false);
  struct Base {
    double max_error = 0, mean_error = 0;
    int vertices = 0;
    HoleCapStats caps;
    MeshReport check;
  };
  auto cap = [&](double wrap_rms) {
    TriangleMesh mesh = *nets;
    HoleCapOptions options;
    options.wrap_rms = wrap_rms;
    Base base;
    EXPECT_TRUE(CapHoles(mesh, kVoxel, open.points, options, &base.caps).ok());
    // The base within 0.8 of its radius: cap, away from the rim's rings. Its distance to
    // the base's plane, in voxels.
    for (const Point3f& p : mesh.vertices) {
      if (p[1] > 0.5 || p[0] * p[0] + p[2] * p[2] > 0.64 * kBottom * kBottom) continue;
      const double e = std::abs(p[1]) / kVoxel;
      base.max_error = std::max(base.max_error, e);
      base.mean_error += e;
      ++base.vertices;
    }
    if (base.vertices > 0) base.mean_error /= base.vertices;
    base.check = CheckMesh(mesh);
    return base;
  };
  const Base planar = cap(HoleCapOptions{}.wrap_rms);
  const Base forced = cap(0.0);
  EXPECT_EQ(planar.caps.regions, 1);
  EXPECT_EQ(planar.caps.harmonic_starts, 1);
  EXPECT_EQ(planar.caps.wrapped, 0);
  EXPECT_EQ(forced.caps.wrapped, 1);
  ASSERT_GT(planar.vertices, 100);
  std::printf("frustum base: mean / max distance to the base's plane, voxels: kept %.2f / %.2f, "
              "converged %.2f / %.2f\n",
              planar.mean_error, planar.max_error, forced.mean_error, forced.max_error);
  // Measured: 0.76 / 1.43 voxels kept, 7.01 / 8.32 converged (the walls' slope carried past
  // the base: a bulge).
  EXPECT_LT(planar.max_error, 2.0);
  EXPECT_GT(forced.mean_error, 4.0);
  testing::ExpectValidReport(planar.check, 1, {0});
  testing::ExpectValidReport(forced.check, 1, {0});
}

// A cap held by a point seen inside its gap (HoleCapOptions::converge_held) keeps the iterated
// plate where its rim alone makes the converged plate bulge away from that point: the
// frustum's open base, with a small patch seen 3 voxels inside the solid above its centre.
TEST(HoleCapRims, HeldOpenFlatBaseKeepsItsIteratedPlate) {
  SmoothSurfaceOptions surface;
  surface.fit = false;  // the surface nets, uncapped
  absl::StatusOr<testing::CloudSurface> closed =
      testing::SmoothSurfaceOfCloud(Frustum(3000, true), surface, kVoxel);
  ASSERT_TRUE(closed.ok()) << closed.status();
  PointCloud open = Frustum(3000, false);
  std::mt19937_64 rng(21);
  std::uniform_real_distribution<double> u(0, 1);
  for (int i = 0; i < 40; ++i) {
    const double r = 0.05 * std::sqrt(u(rng)), a = 2 * M_PI * u(rng);
    open.points.push_back(ToPoint3f(Vec3d{r * std::cos(a), 3 * kVoxel, r * std::sin(a)}));
  }
  struct Base {
    double mean_error = 0;  // voxels from the base's plane, within 0.8 of its radius
    HoleCapStats caps;
    MeshReport check;
  };
  auto cap = [&](double held_margin) {
    TriangleMesh mesh = closed->mesh;
    HoleCapOptions options;
    options.held_margin = held_margin;
    Base base;
    EXPECT_TRUE(CapHoles(mesh, kVoxel, open.points, options, &base.caps).ok());
    int count = 0;
    for (const Point3f& p : mesh.vertices) {
      if (p[1] > 0.5 || p[0] * p[0] + p[2] * p[2] > 0.64 * kBottom * kBottom) continue;
      base.mean_error += std::abs(p[1]) / kVoxel;
      ++count;
    }
    if (count > 0) base.mean_error /= count;
    base.check = CheckMesh(mesh);
    return base;
  };
  const Base judged = cap(HoleCapOptions{}.held_margin);
  const Base forced = cap(1e9);  // every held cap converges
  EXPECT_GT(judged.caps.anchors, 0);
  EXPECT_EQ(judged.caps.held_converged, 0);
  EXPECT_EQ(forced.caps.held_converged, 1);
  std::printf("frustum base held at a seen patch: mean distance to the base's plane, voxels: "
              "judged %.2f, converged %.2f\n",
              judged.mean_error, forced.mean_error);
  // Measured: 1.28 voxels judged, 1.82 converged (the held vertices at the centre keep the
  // bulge from the walls' slope down to a ring around them; without the patch: 7.01); the
  // judge's trial without the holds: 2.25 voxels from the patch iterated, 11.32 converged.
  EXPECT_LT(judged.mean_error, 1.5);
  EXPECT_GT(forced.mean_error, judged.mean_error + 0.4);
  testing::ExpectValidReport(judged.check, 1, {0});
  testing::ExpectValidReport(forced.check, 1, {0});
}

}  // namespace
}  // namespace membrane
