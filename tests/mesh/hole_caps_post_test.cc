// Caps over the end of a post that a hole swallowed (core/mesh/hole_caps.h, swept_length): the
// walls run on past the rim instead of being cut off where the data end.
#include <algorithm>
#include <cmath>
#include <cstdio>
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

constexpr double kPostVoxel = 0.05;

// A square post |x|, |z| <= 0.4 (16 voxels wide), -2 <= y <= 1, sampled on its faces but for
// no point within 1 of (0, 0.9, 0): the hole swallows its top face and its walls down to
// y = -0.02 .. 0.08, about 20 voxels of the post.
constexpr double kPostHalfWidth = 0.4, kPostTop = 1.0;
const Vec3d kPostHole{0, 0.9, 0};
constexpr double kPostHoleRadius = 1.0;

PointCloud PostWithHole() {
  std::mt19937_64 rng(3);
  return testing::BoxFacePoints(
      Vec3d{-kPostHalfWidth, -2, -kPostHalfWidth},
      Vec3d{kPostHalfWidth, kPostTop, kPostHalfWidth}, 3000, rng, [](const Vec3d& p) {
        return SquaredNorm(p - kPostHole) >= kPostHoleRadius * kPostHoleRadius;
      });
}

struct PostCap {
  double reach = 0;       // the mesh's highest vertex above the rim's highest point, voxels
  double wall_error = 0;  // mean distance from the post's walls of the cap's vertices beside them
  HoleCapStats caps;
  MeshReport check;
};

PostCap ReconstructPost(double swept_length) {
  SmoothSurfaceOptions options;
  options.hole_caps.swept_length = swept_length;
  // This rim is a square loop round the walls, in its plane, its band's normals square to the
  // plane's: a height field. The rims of the posts that a hole swallows off their axis wrap
  // (the rocker arm's: normals turned back, RMS 6.9-7.4 voxels off their plane); here the rim
  // is taken as one of those, to measure the sweep alone.
  options.hole_caps.min_rim_cosine = 1;
  options.hole_caps.wrap_rms = 0;
  auto surface = testing::SmoothSurfaceOfCloud(PostWithHole(), options, kPostVoxel);
  EXPECT_TRUE(surface.ok()) << surface.status();
  PostCap out;
  if (!surface.ok()) return out;
  out.caps = surface->stats.caps;
  out.check = CheckMesh(surface->mesh);
  const double rim = kPostHole[1] - std::sqrt(kPostHoleRadius * kPostHoleRadius -
                                               2 * kPostHalfWidth * kPostHalfWidth);
  double top = -std::numeric_limits<double>::infinity();
  double sum = 0;
  int count = 0;
  for (const Point3f& p : surface->mesh.vertices) {
    const Vec3d v = ToVec3d(p);
    top = std::max(top, v[1]);
    // Beside a wall, below the post's top: the walls' continuation.
    const double side = std::max(std::abs(v[0]), std::abs(v[2]));
    if (v[1] > rim && v[1] < kPostTop - 0.2 && side > kPostHalfWidth - 0.15) {
      sum += std::abs(side - kPostHalfWidth);
      ++count;
    }
  }
  out.reach = (top - rim) / kPostVoxel;
  out.wall_error = count > 0 ? sum / count / kPostVoxel : 0;
  return out;
}

TEST(HoleCapPosts, SweptCapContinuesThePostsWalls) {
  const PostCap swept = ReconstructPost(HoleCapOptions{}.swept_length);
  const PostCap plate = ReconstructPost(0);
  EXPECT_EQ(swept.caps.wrapped, 1);
  EXPECT_EQ(swept.caps.swept, 1);
  EXPECT_EQ(plate.caps.swept, 0);
  std::printf("post end: reach above the rim %.2f voxels swept, %.2f converged plate (the post "
              "runs %.2f on); walls %.2f / %.2f voxels off\n",
              swept.reach, plate.reach,
              (kPostTop - kPostHole[1] + std::sqrt(kPostHoleRadius * kPostHoleRadius -
                                           2 * kPostHalfWidth * kPostHalfWidth)) / kPostVoxel,
              swept.wall_error, plate.wall_error);
  EXPECT_GT(swept.reach, plate.reach + 4);
  EXPECT_LT(swept.wall_error, 1.5);
  testing::ExpectValidReport(swept.check, 1, {0});
  testing::ExpectValidReport(plate.check, 1, {0});
}

}  // namespace
}  // namespace membrane
