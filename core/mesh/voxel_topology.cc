#include "core/mesh/voxel_topology.h"

#include <array>
#include <bit>
#include <cstdint>

namespace membrane {
namespace {

// Euler characteristic contributed by the cubical cells whose lowest corner is a lattice point,
// as a function of the 8 voxels around it (bit o = voxel at octant o, bit k of o set = the +
// side along axis k). Summed over all lattice points it gives V - E + F - C of the union of
// closed cubes, because every cell has exactly one lowest corner.
int LocalEuler(int config) {
  if (config == 0) return 0;
  auto solid = [&](int o) { return (config >> o) & 1; };
  int v = 1, e = 0, f = 0;
  for (int a = 0; a < 3; ++a) {
    bool edge = false, face = false;
    for (int o = 0; o < 8; ++o) {
      // The edge from the point along +a touches the 4 voxels on the + side of a.
      if (((o >> a) & 1) && solid(o)) edge = true;
    }
    // The face spanned by +u, +v (perpendicular to a) touches the 2 voxels on the + side of u
    // and v.
    const int u = (a + 1) % 3, w = (a + 2) % 3;
    for (int o = 0; o < 8; ++o)
      if (((o >> u) & 1) && ((o >> w) & 1) && solid(o)) face = true;
    e += edge;
    f += face;
  }
  const int c = solid(7);
  return v - e + f - c;
}

}  // namespace

VoxelTopology ComputeVoxelTopology(const VoxelGrid& grid) {
  static constexpr int kUnlabelled = -1;
  VoxelTopology topo;
  const auto& dims = grid.dims();
  std::vector<int32_t> label(static_cast<size_t>(grid.size()), kUnlabelled);
  std::vector<int64_t> stack;
  for (int64_t i = 0; i < grid.size(); ++i) {
    if (IsOutside(grid.at(i)) || label[i] != kUnlabelled) continue;
    const int32_t id = topo.shells++;
    label[i] = id;
    stack.push_back(i);
    while (!stack.empty()) {
      const Coord c = grid.CoordOf(stack.back());
      stack.pop_back();
      for (int dz = -1; dz <= 1; ++dz)
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            const Coord n{c.x + dx, c.y + dy, c.z + dz};
            if (!grid.Contains(n)) continue;
            const int64_t j = grid.Index(n);
            if (IsOutside(grid.at(j)) || label[j] != kUnlabelled) continue;
            label[j] = id;
            stack.push_back(j);
          }
    }
  }
  std::array<int, 256> euler;
  for (int k = 0; k < 256; ++k) euler[k] = LocalEuler(k);
  std::vector<int64_t> chi(topo.shells, 0);
  // Lattice point (x, y, z) is the lowest corner of voxel (x, y, z); its 8 voxels are
  // (x-1..x, y-1..y, z-1..z). Points on the array's outer faces touch only border voxels,
  // which are outside.
  for (int z = 1; z < dims[2]; ++z)
    for (int y = 1; y < dims[1]; ++y)
      for (int x = 1; x < dims[0]; ++x) {
        int config = 0, any = -1;
        for (int o = 0; o < 8; ++o) {
          const int64_t j = grid.Index(x - 1 + (o & 1), y - 1 + ((o >> 1) & 1), z - 1 + (o >> 2));
          if (!IsOutside(grid.at(j))) {
            config |= 1 << o;
            any = label[j];
          }
        }
        if (config != 0) chi[any] += euler[config];
      }
  for (int s = 0; s < topo.shells; ++s) topo.genus.push_back(static_cast<int>(1 - chi[s]));
  return topo;
}

}  // namespace membrane
