#include "tests/support/cup_cloud.h"

#include <array>
#include <cmath>
#include <numbers>
#include <random>

#include "core/engine/voxelization.h"

namespace membrane::testing {

double CupVoxelSize(int64_t points) {
  Box3d box;
  box.min = {-kCupRadius, -kCupRadius, 0.0};
  box.max = {kCupRadius, kCupRadius, kCupHeight};
  return EstimateVoxelSize(box, points);
}

double CupSolidVolume(double wall) {
  const double r = kCupRadius - wall;
  return CupCylinderVolume() - std::numbers::pi * r * r * (kCupHeight - wall);
}

double CupCylinderVolume() { return std::numbers::pi * kCupRadius * kCupRadius * kCupHeight; }

PointCloud CupCloud(double wall_voxels, int64_t points, uint64_t seed) {
  const double t = wall_voxels * CupVoxelSize(points);
  const double R = kCupRadius, H = kCupHeight, r = R - t, pi = std::numbers::pi;
  // Outer side, inner side, outer bottom, inner bottom, rim: areas, sampled in proportion.
  const std::array<double, 5> area = {2 * pi * R * H, 2 * pi * r * (H - t), pi * R * R,
                                      pi * r * r, pi * (R * R - r * r)};
  double total = 0;
  for (double a : area) total += a;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  PointCloud cloud;
  cloud.points.reserve(static_cast<size_t>(points));
  for (int64_t i = 0; i < points; ++i) {
    double pick = unit(rng) * total;
    int part = 0;
    while (part < 4 && pick >= area[part]) pick -= area[part++];
    const double angle = 2 * pi * unit(rng);
    double radius = R, z = 0;
    switch (part) {
      case 0: z = H * unit(rng); break;
      case 1: radius = r, z = t + (H - t) * unit(rng); break;
      case 2: radius = R * std::sqrt(unit(rng)); break;
      case 3: radius = r * std::sqrt(unit(rng)), z = t; break;
      default: radius = std::sqrt(r * r + (R * R - r * r) * unit(rng)), z = H; break;
    }
    cloud.points.push_back({static_cast<float>(radius * std::cos(angle)),
                            static_cast<float>(radius * std::sin(angle)), static_cast<float>(z)});
  }
  return cloud;
}

}  // namespace membrane::testing
