#include "tests/mesh/test_grids.h"

#include <cmath>
#include <random>

namespace membrane::testing {

VoxelGrid OutsideGrid(int n, double voxel_size, std::array<double, 3> origin) {
  return VoxelGrid({n, n, n}, origin, voxel_size, OutsideState(0));
}

void ClassifyMembrane(VoxelGrid& grid, VoxelState boundary, VoxelState inside) {
  const auto& d = grid.dims();
  VoxelStates next = grid.states();
  for (int z = 0; z < d[2]; ++z)
    for (int y = 0; y < d[1]; ++y)
      for (int x = 0; x < d[0]; ++x) {
        const Coord c{x, y, z};
        if (IsOutside(grid.at(c))) continue;
        bool touches_outside = false;
        for (int dz = -1; dz <= 1; ++dz)
          for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
              const Coord n{x + dx, y + dy, z + dz};
              if (!grid.Contains(n) || IsOutside(grid.at(n))) touches_outside = true;
            }
        next[grid.Index(c)] = touches_outside ? boundary : inside;
      }
  grid.mutable_states() = std::move(next);
}

void MarkSolid(VoxelGrid& grid, const std::function<bool(int, int, int)>& solid,
               VoxelState boundary, VoxelState inside) {
  const auto& d = grid.dims();
  for (int z = 0; z < d[2]; ++z)
    for (int y = 0; y < d[1]; ++y)
      for (int x = 0; x < d[0]; ++x)
        if (solid(x, y, z)) grid.set(Coord{x, y, z}, inside);
  ClassifyMembrane(grid, boundary, inside);
}

VoxelGrid BallGrid(int n, double radius) {
  VoxelGrid g = OutsideGrid(n);
  const double c = n / 2.0;
  MarkSolid(g, [&](int x, int y, int z) {
    const double dx = x + 0.5 - c, dy = y + 0.5 - c, dz = z + 0.5 - c;
    return dx * dx + dy * dy + dz * dz <= radius * radius;
  });
  return g;
}

VoxelGrid SolidTorusGrid(int n, double major_radius, double minor_radius) {
  VoxelGrid g = OutsideGrid(n);
  const double c = n / 2.0;
  MarkSolid(g, [&](int x, int y, int z) {
    const double dx = x + 0.5 - c, dy = y + 0.5 - c, dz = z + 0.5 - c;
    const double ring = std::sqrt(dx * dx + dy * dy) - major_radius;
    return ring * ring + dz * dz <= minor_radius * minor_radius;
  });
  return g;
}

VoxelGrid TwoBallsGrid(int n, double radius, double gap) {
  VoxelGrid g = OutsideGrid(n);
  const double c = n / 2.0, offset = radius + gap / 2;
  MarkSolid(g, [&](int x, int y, int z) {
    const double dy = y + 0.5 - c, dz = z + 0.5 - c;
    for (double cx : {c - offset, c + offset}) {
      const double dx = x + 0.5 - cx;
      if (dx * dx + dy * dy + dz * dz <= radius * radius) return true;
    }
    return false;
  });
  return g;
}

VoxelGrid EdgeContactGrid() {
  VoxelGrid g = OutsideGrid(7);
  g.set(Coord{3, 3, 3}, kBoundaryHard);
  g.set(Coord{4, 4, 3}, kBoundaryHard);
  return g;
}

VoxelGrid CornerContactGrid() {
  VoxelGrid g = OutsideGrid(7);
  g.set(Coord{3, 3, 3}, kBoundaryHard);
  g.set(Coord{4, 4, 4}, kBoundaryHard);
  return g;
}

VoxelGrid ThickEdgeContactGrid() {
  VoxelGrid g = OutsideGrid(14);
  MarkSolid(g, [](int x, int y, int z) {
    const bool a = x >= 2 && x < 6 && y >= 2 && y < 6 && z >= 4 && z < 8;
    const bool b = x >= 6 && x < 10 && y >= 6 && y < 10 && z >= 4 && z < 8;
    return a || b;
  });
  return g;
}

VoxelGrid ThickCornerContactGrid() {
  VoxelGrid g = OutsideGrid(14);
  MarkSolid(g, [](int x, int y, int z) {
    const bool a = x >= 2 && x < 6 && y >= 2 && y < 6 && z >= 2 && z < 6;
    const bool b = x >= 6 && x < 10 && y >= 6 && y < 10 && z >= 6 && z < 10;
    return a || b;
  });
  return g;
}

VoxelGrid PinholeBoxGrid(int n, int wall) {
  VoxelGrid g = OutsideGrid(n);
  const int lo = 2, hi = n - 3;  // solid spans [lo, hi]
  const int mid = n / 2;
  MarkSolid(g, [&](int x, int y, int z) {
    if (x < lo || y < lo || z < lo || x > hi || y > hi || z > hi) return false;
    const bool in_wall = x < lo + wall || y < lo + wall || z < lo + wall || x > hi - wall ||
                         y > hi - wall || z > hi - wall;
    if (!in_wall) return false;
    const bool pinhole = x == mid && y == mid && z < lo + wall;
    return !pinhole;
  });
  return g;
}

void FillCavities(VoxelGrid& grid) {
  const auto& d = grid.dims();
  std::vector<char> reached(grid.size(), 0);
  std::vector<int64_t> stack;
  for (int64_t i = 0; i < grid.size(); ++i)
    if (grid.OnArrayBorder(grid.CoordOf(i)) && IsOutside(grid.at(i))) {
      reached[i] = 1;
      stack.push_back(i);
    }
  while (!stack.empty()) {
    const Coord c = grid.CoordOf(stack.back());
    stack.pop_back();
    for (int a = 0; a < 3; ++a)
      for (int s : {-1, 1}) {
        Coord n = c;
        n[a] += s;
        if (!grid.Contains(n)) continue;
        const int64_t j = grid.Index(n);
        if (reached[j] || !IsOutside(grid.at(j))) continue;
        reached[j] = 1;
        stack.push_back(j);
      }
  }
  (void)d;
  for (int64_t i = 0; i < grid.size(); ++i)
    if (IsOutside(grid.at(i)) && !reached[i]) grid.set(i, kInsideSoft);
}

VoxelGrid RandomSolidGrid(int n, double p, uint32_t seed) {
  VoxelGrid g = OutsideGrid(n);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  for (int z = 2; z < n - 2; ++z)
    for (int y = 2; y < n - 2; ++y)
      for (int x = 2; x < n - 2; ++x)
        if (u(rng) < p) g.set(Coord{x, y, z}, kInsideSoft);
  FillCavities(g);
  ClassifyMembrane(g);
  return g;
}

std::vector<Point3f> SpherePoints(int count, std::array<double, 3> centre, double radius,
                                  uint32_t seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal(0, 1);
  std::vector<Point3f> points;
  points.reserve(count);
  for (int i = 0; i < count; ++i) {
    double v[3] = {normal(rng), normal(rng), normal(rng)};
    const double len = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    points.push_back({static_cast<float>(centre[0] + radius * v[0] / len),
                      static_cast<float>(centre[1] + radius * v[1] / len),
                      static_cast<float>(centre[2] + radius * v[2] / len)});
  }
  return points;
}

VoxelGrid SampledSphereGrid(int n, double voxel_size, std::array<double, 3> centre, double radius,
                            const std::vector<Point3f>& points) {
  VoxelGrid g = OutsideGrid(n, voxel_size);
  for (const Point3f& p : points) {
    const Coord c{static_cast<int>(std::floor(p[0] / voxel_size)),
                  static_cast<int>(std::floor(p[1] / voxel_size)),
                  static_cast<int>(std::floor(p[2] / voxel_size))};
    g.set(c, kInsideSoft);
  }
  MarkSolid(g, [&](int x, int y, int z) {
    const auto m = g.Center(Coord{x, y, z});
    const double dx = m[0] - centre[0], dy = m[1] - centre[1], dz = m[2] - centre[2];
    return dx * dx + dy * dy + dz * dz <= radius * radius;
  });
  // An outside voxel boxed in by point voxels and the ball would be a cavity.
  FillCavities(g);
  ClassifyMembrane(g);
  return g;
}

}  // namespace membrane::testing
