// Caps held by points seen inside their gap converge (core/mesh/hole_caps.h, converge_held): a
// ball whose top is cut flat, scanned all over but on the flat top, where the scanner saw a few
// small patches. As under spot's belly, the membrane spans the unscanned part outside the
// solid (here: the whole ball's dome), the patches lie inside it, and the band around the hole
// continues the ball's curve into that dome. The held patches pull the cap down to the flat
// top; the converged plate carries them across the hole where 60 iterations from the spline
// leave a tent around each.
#include <algorithm>
#include <cmath>
#include <random>
#include <string_view>
#include <vector>

#include "core/mesh/hole_caps.h"
#include "core/mesh/mesh_check.h"
#include "core/mesh/smooth_surface.h"
#include "gtest/gtest.h"
#include "tests/mesh/cloud_surface.h"
#include "tests/mesh/surface_expectations.h"

namespace membrane {
namespace {

// The unit ball cut by the plane z = kCutHeight: the flat top is a disc of radius
// sqrt(1 - kCutHeight^2) (0.71), about 36 voxels across at the voxel the test uses.
constexpr double kCutHeight = 0.7;
constexpr double kCutBallVoxel = 0.04;
// Where the scanner saw the flat top: discs of this radius around these centres (x, y).
constexpr double kSeenPatchRadius = 0.04;
constexpr double kSeenPatches[][2] = {{0, 0}, {0.35, 0}, {-0.35, 0}, {0, 0.35}, {0, -0.35}};

PointCloud CutBallSeenInPatches(int per_unit_area) {
  std::mt19937_64 rng(13);
  std::normal_distribution<double> gauss;
  std::uniform_real_distribution<double> u(0, 1);
  PointCloud cloud;
  // The sphere's part below the cut, area-uniform (4 pi r^2 of the whole sphere).
  const int sphere = static_cast<int>(per_unit_area * 4 * M_PI);
  for (int i = 0; i < sphere; ++i) {
    const Vec3d p = Normalized(Vec3d{gauss(rng), gauss(rng), gauss(rng)});
    if (p[2] <= kCutHeight) cloud.points.push_back(ToPoint3f(p));
  }
  const int per_patch = static_cast<int>(per_unit_area * M_PI * kSeenPatchRadius * kSeenPatchRadius);
  for (const auto& c : kSeenPatches)
    for (int i = 0; i < per_patch; ++i) {
      const double r = kSeenPatchRadius * std::sqrt(u(rng)), a = 2 * M_PI * u(rng);
      cloud.points.push_back(
          ToPoint3f(Vec3d{c[0] + r * std::cos(a), c[1] + r * std::sin(a), kCutHeight}));
    }
  return cloud;
}

PointCloud Ball(int per_unit_area) {
  std::mt19937_64 rng(17);
  std::normal_distribution<double> gauss;
  PointCloud cloud;
  const int n = static_cast<int>(per_unit_area * 4 * M_PI);
  for (int i = 0; i < n; ++i)
    cloud.points.push_back(ToPoint3f(Normalized(Vec3d{gauss(rng), gauss(rng), gauss(rng)})));
  return cloud;
}

// The surface nets of the whole ball at kCutBallVoxel, uncapped and unfitted: the caps' input.
absl::StatusOr<testing::CloudSurface> UncappedBall() {
  SmoothSurfaceOptions surface;
  surface.fit = false;
  return testing::SmoothSurfaceOfCloud(Ball(4000), surface, kCutBallVoxel);
}

struct Top {
  double max_error = 0, mean_error = 0;  // voxels from the flat top's plane
  int vertices = 0;
  HoleCapStats caps;
  MeshReport check;
};

// The caps are given the surface nets of the whole ball and the cut ball's cloud.
TEST(HoleCapHeld, SeenPatchesCarryTheConvergedCapToTheFlatTop) {
  const absl::StatusOr<testing::CloudSurface> ball = UncappedBall();
  ASSERT_TRUE(ball.ok()) << ball.status();
  const PointCloud cloud = CutBallSeenInPatches(4000);
  auto cap = [&](bool converge_held) {
    TriangleMesh mesh = ball->mesh;
    HoleCapOptions options;
    options.converge_held = converge_held;
    Top top;
    EXPECT_TRUE(CapHoles(mesh, kCutBallVoxel, cloud.points, options, &top.caps).ok());
    // The flat top within 0.45 of its axis (the rim's rings lie outside).
    for (const Point3f& p : mesh.vertices) {
      if (p[2] < 0.5 || p[0] * p[0] + p[1] * p[1] > 0.5 * 0.5) continue;
      const double e = std::abs(p[2] - kCutHeight) / kCutBallVoxel;
      top.max_error = std::max(top.max_error, e);
      top.mean_error += e;
      ++top.vertices;
    }
    if (top.vertices > 0) top.mean_error /= top.vertices;
    top.check = CheckMesh(mesh);
    return top;
  };
  const Top held = cap(true);
  const Top iterated = cap(false);
  EXPECT_EQ(held.caps.regions, 1);
  EXPECT_GT(held.caps.anchors, 0);
  EXPECT_EQ(held.caps.held_converged, 1);
  EXPECT_EQ(iterated.caps.held_converged, 0);
  ASSERT_GT(held.vertices, 100);
  std::printf("cut ball: mean / max distance to the flat top, voxels: converged through the "
              "held points %.2f / %.2f, 60 iterations %.2f / %.2f\n",
              held.mean_error, held.max_error, iterated.mean_error, iterated.max_error);
  // Measured: 0.37 / 1.37 voxels converged, 2.82 / 8.17 with 60 iterations (the dome the
  // spline continues from the ball stands 7.5 voxels over the flat top's centre).
  EXPECT_LT(held.mean_error, 1.0);
  EXPECT_LT(held.max_error, 2.0);
  EXPECT_GT(iterated.mean_error, held.mean_error + 1.0);
  testing::ExpectValidReport(held.check, 1, {0});
  testing::ExpectValidReport(iterated.check, 1, {0});
}

// The cut ball's cloud, and its bottom below kBottomCut cut too: a second hole (30 voxels
// across), seen in patches as the top is.
constexpr double kBottomCut = -0.8;
PointCloud CutTwiceSeenInPatches(int per_unit_area) {
  PointCloud cloud = CutBallSeenInPatches(per_unit_area);
  std::erase_if(cloud.points, [](const Point3f& p) { return p[2] < kBottomCut; });
  std::mt19937_64 rng(19);
  std::uniform_real_distribution<double> u(0, 1);
  const int per_patch = static_cast<int>(per_unit_area * M_PI * kSeenPatchRadius * kSeenPatchRadius);
  for (const auto& c : kSeenPatches)
    for (int i = 0; i < per_patch; ++i) {
      const double r = kSeenPatchRadius * std::sqrt(u(rng)), a = 2 * M_PI * u(rng);
      cloud.points.push_back(ToPoint3f(
          Vec3d{0.5 * c[0] + r * std::cos(a), 0.5 * c[1] + r * std::sin(a), kBottomCut}));
    }
  return cloud;
}

// Each cap that converges is solved on its own: the top's plate is the same with the bottom
// hole capped on the same mesh (a solve over both caps shares one step length and one
// stopping test between them).
TEST(HoleCapHeld, AConvergedCapDoesNotDependOnAnotherCap) {
  const absl::StatusOr<testing::CloudSurface> ball = UncappedBall();
  ASSERT_TRUE(ball.ok()) << ball.status();
  auto cap = [&](const PointCloud& cloud, HoleCapStats& stats) {
    TriangleMesh mesh = ball->mesh;
    HoleCapOptions options;
    options.wrapped_iterations = 400;
    // Every held cap converges: the bottom's trial would keep its 60 iterations otherwise.
    options.held_margin = 1000;
    EXPECT_TRUE(CapHoles(mesh, kCutBallVoxel, cloud.points, options, &stats).ok());
    testing::ExpectValidReport(CheckMesh(mesh), 1, {0});
    return mesh;
  };
  HoleCapStats one, two;
  const TriangleMesh top_only = cap(CutBallSeenInPatches(4000), one);
  const TriangleMesh both = cap(CutTwiceSeenInPatches(4000), two);
  EXPECT_EQ(one.regions, 1);
  EXPECT_EQ(one.held_converged, 1);
  EXPECT_EQ(two.regions, 2);
  EXPECT_EQ(two.held_converged, 2);
  double largest = 0;
  int top = 0;
  for (size_t v = 0; v < top_only.vertices.size(); ++v) {
    const Point3f& p = top_only.vertices[v];
    if (p[2] < 0.5) continue;
    ++top;
    largest = std::max(largest, Norm(ToVec3d(both.vertices[v]) - ToVec3d(p)) / kCutBallVoxel);
  }
  ASSERT_GT(top, 100);
  std::printf("top cap, %d vertices: largest move with the bottom's cap beside it %.4f voxel "
              "(iterations %lld alone, %lld with both)\n",
              top, largest, static_cast<long long>(one.iterations),
              static_cast<long long>(two.iterations));
  // Measured: 0.0000 voxel; 0.0162 with both caps solved as one system.
  EXPECT_LT(largest, 0.002);
}

// A converging cap past coarse_plate_vertices starts from the coarse plate: with as few
// iterations as leave the plain conjugate gradients in the dome the spline lifts, it reaches
// the flat top as the converged cap does (a 10M-point scan's open base, 609,518 vertices, in
// miniature: here cells of 5 voxels, about 40 clusters).
TEST(HoleCapHeld, ALargeCapConvergesFromTheCoarsePlate) {
  const absl::StatusOr<testing::CloudSurface> ball = UncappedBall();
  ASSERT_TRUE(ball.ok()) << ball.status();
  const PointCloud cloud = CutBallSeenInPatches(4000);
  auto cap = [&](int iterations, int64_t coarse_vertices) {
    TriangleMesh mesh = ball->mesh;
    HoleCapOptions options;
    options.wrapped_iterations = iterations;
    options.coarse_plate_vertices = coarse_vertices;
    options.coarse_plate_clusters = 64;
    Top top;
    EXPECT_TRUE(CapHoles(mesh, kCutBallVoxel, cloud.points, options, &top.caps).ok());
    for (const Point3f& p : mesh.vertices) {
      if (p[2] < 0.5 || p[0] * p[0] + p[1] * p[1] > 0.5 * 0.5) continue;
      top.mean_error += std::abs(p[2] - kCutHeight) / kCutBallVoxel;
      ++top.vertices;
    }
    if (top.vertices > 0) top.mean_error /= top.vertices;
    testing::ExpectValidReport(CheckMesh(mesh), 1, {0});
    return top;
  };
  const Top converged = cap(1000, int64_t{1} << 17);
  const Top plain = cap(40, int64_t{1} << 17);
  const Top coarse = cap(40, 256);
  EXPECT_EQ(coarse.caps.held_converged, 1);
  ASSERT_GT(coarse.vertices, 100);
  std::printf("cut ball: mean distance to the flat top, voxels: converged %.2f (%lld "
              "iterations), 40 iterations %.2f, 40 from the coarse plate %.2f\n",
              converged.mean_error, static_cast<long long>(converged.caps.iterations),
              plain.mean_error, coarse.mean_error);
  EXPECT_LT(coarse.mean_error, converged.mean_error + 0.25);
  EXPECT_GT(plain.mean_error, coarse.mean_error + 0.5);
}

TEST(HoleCapHeld, RefusesANegativeMargin) {
  TriangleMesh mesh;
  for (double margin : {-0.1, std::nan("")}) {
    HoleCapOptions options;
    options.held_margin = margin;
    EXPECT_EQ(CapHoles(mesh, 1.0, {}, options).code(), absl::StatusCode::kInvalidArgument)
        << margin;
  }
}

// The coarse plate's options out of range are refused, each named in the message.
TEST(HoleCapHeld, RefusesCoarsePlateOptionsOutOfRange) {
  TriangleMesh mesh;
  for (int k = 0; k < 4; ++k) {
    HoleCapOptions options;
    if (k == 0) options.coarse_plate_vertices = 0;
    if (k == 1) options.coarse_plate_clusters = 0;
    if (k == 2) options.coarse_plate_clusters = (int64_t{1} << 24) + 1;
    if (k == 3) options.coarse_plate_iterations = -1;
    const absl::Status status = CapHoles(mesh, 1.0, {}, options);
    EXPECT_EQ(status.code(), absl::StatusCode::kInvalidArgument) << k;
    EXPECT_NE(status.message().find("coarse_plate_"), std::string_view::npos) << status;
  }
}

}  // namespace
}  // namespace membrane
