#include "core/mesh/corner_crease.h"

#include <cmath>
#include <random>
#include <vector>

#include "gtest/gtest.h"

namespace membrane {
namespace {

// The band around a hole over a concave corner: a floor z = 0 (x from `near` to `far`, normal
// +z) meeting a wall x = 0 (z from `near` to `far`, normal +x) along the y axis, a member a
// unit apart, y in [-20, 20].
struct Band {
  std::vector<Vec3d> positions, normals;
};

Band CornerBand(double near, double far) {
  Band band;
  for (double y = -20; y <= 20; y += 1)
    for (double s = near; s <= far; s += 1) {
      band.positions.push_back({s, y, 0});
      band.normals.push_back({0, 0, 1});
      band.positions.push_back({0, y, s});
      band.normals.push_back({1, 0, 0});
    }
  return band;
}

const Vec3d kAxis = Normalized(Vec3d{1, 0, 1});

// A fillet's positions at height h above both the floor and the wall, y in [-5, 5].
std::vector<Vec3d> Fillet(double h) {
  std::vector<Vec3d> cap;
  for (double y = -5; y <= 5; y += 1) cap.push_back({h, y, h});
  return cap;
}

TEST(CornerCrease, MovesAFilletOntoTheCorner) {
  const Band band = CornerBand(2, 12);
  std::vector<Vec3d> cap = Fillet(3);
  const int moved = CreaseToCorner(band.positions, band.normals, kAxis, CornerCreaseOptions(),
                                   absl::MakeSpan(cap));
  EXPECT_EQ(moved, static_cast<int>(cap.size()));
  for (const Vec3d& p : cap) {
    // Along the normals' mean to the first plane: both planes meet there, on the corner.
    EXPECT_NEAR(p[0], 0, 1e-9);
    EXPECT_NEAR(p[2], 0, 1e-9);
  }
}

TEST(CornerCrease, LeavesAPositionInsideASideAlone) {
  const Band band = CornerBand(2, 12);
  // Below the floor: inside the union of the two solids already.
  std::vector<Vec3d> cap = {{3, 0, -1}, {-1, 2, 3}};
  const std::vector<Vec3d> before = cap;
  EXPECT_EQ(CreaseToCorner(band.positions, band.normals, kAxis, CornerCreaseOptions(),
                           absl::MakeSpan(cap)),
            0);
  EXPECT_EQ(cap, before);
}

// Beyond `reach` the band is read by cells, each as one member at its members' mean: a band
// far from the fillet still shows the corner, and the move stops at max_move, as when every
// member is read one by one.
TEST(CornerCrease, ReadsTheFarBandByCells) {
  const Band band = CornerBand(2, 12);
  const double h = 60;  // the nearest band member lies sqrt(48^2 + 60^2) = 76.8 away
  const std::vector<Vec3d> fillet = Fillet(h);
  for (const double reach : {16.0, 64.0, 200.0}) {
    std::vector<Vec3d> cap = fillet;
    CornerCreaseOptions options;
    options.reach = reach;
    EXPECT_EQ(CreaseToCorner(band.positions, band.normals, kAxis, options, absl::MakeSpan(cap)),
              static_cast<int>(cap.size()))
        << "reach " << reach;
    for (size_t i = 0; i < cap.size(); ++i) {
      EXPECT_NEAR(Norm(cap[i] - fillet[i]), options.max_move, 1e-9) << "reach " << reach;
      EXPECT_NEAR(cap[i][0], cap[i][2], 1e-9) << "reach " << reach;
    }
  }
}

TEST(CornerCrease, GivesTheSameMovesOnAnyThreadCount) {
  Band band = CornerBand(1, 40);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> jitter(-0.3, 0.3), spread(0.5, 30);
  for (Vec3d& p : band.positions) p = p + Vec3d{jitter(rng), jitter(rng), jitter(rng)};
  std::vector<Vec3d> cap;
  for (int i = 0; i < 2000; ++i) cap.push_back({spread(rng), spread(rng) - 15, spread(rng)});
  std::vector<Vec3d> two = cap;
  const int moved_one = CreaseToCorner(band.positions, band.normals, kAxis,
                                       CornerCreaseOptions(), absl::MakeSpan(cap), 1);
  const int moved_two = CreaseToCorner(band.positions, band.normals, kAxis,
                                       CornerCreaseOptions(), absl::MakeSpan(two), 2);
  EXPECT_GT(moved_one, 400);
  EXPECT_EQ(moved_one, moved_two);
  EXPECT_EQ(cap, two);
}

}  // namespace
}  // namespace membrane
