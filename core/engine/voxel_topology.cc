#include "core/engine/voxel_topology.h"

#include <array>
#include <bit>

namespace membrane {
namespace {

// 8 x the Euler characteristic contributed by one lattice vertex, for each configuration of
// its 8 incident voxels (bit dx + 2 dy + 4 dz): 8 V - 4 E + 2 F - C, since an edge has two
// end vertices, a square face four corners and a cube eight.
constexpr std::array<int, 256> MakeEulerTable() {
  std::array<int, 256> table{};
  for (int m = 0; m < 256; ++m) {
    auto has = [m](int dx, int dy, int dz) { return ((m >> (dx + 2 * dy + 4 * dz)) & 1) != 0; };
    int vertices = m != 0 ? 1 : 0;
    int edges = 0, faces = 0, cubes = 0;
    for (int b = 0; b < 8; ++b) cubes += (m >> b) & 1;
    // Edges along axis a, on side s (the voxels with coordinate a equal to s).
    for (int a = 0; a < 3; ++a)
      for (int side = 0; side < 2; ++side) {
        bool any = false;
        for (int p = 0; p < 2; ++p)
          for (int q = 0; q < 2; ++q) {
            int c[3];
            c[a] = side;
            c[(a + 1) % 3] = p;
            c[(a + 2) % 3] = q;
            any = any || has(c[0], c[1], c[2]);
          }
        edges += any;
      }
    // Faces normal to axis a, in quadrant (p, q) of the other two axes.
    for (int a = 0; a < 3; ++a)
      for (int p = 0; p < 2; ++p)
        for (int q = 0; q < 2; ++q) {
          bool any = false;
          for (int side = 0; side < 2; ++side) {
            int c[3];
            c[a] = side;
            c[(a + 1) % 3] = p;
            c[(a + 2) % 3] = q;
            any = any || has(c[0], c[1], c[2]);
          }
          faces += any;
        }
    table[static_cast<size_t>(m)] = 8 * vertices - 4 * edges + 2 * faces - cubes;
  }
  return table;
}

constexpr std::array<int, 256> kEulerTable = MakeEulerTable();

}  // namespace

int LabelShells(const VoxelGrid& grid, std::vector<int32_t>& label) {
  const int64_t nv = grid.size();
  const auto st = grid.strides();
  label.assign(static_cast<size_t>(nv), -1);
  int64_t offsets[26];
  int k = 0;
  for (int dz = -1; dz <= 1; ++dz)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx)
        if (dx != 0 || dy != 0 || dz != 0) offsets[k++] = dx * st[0] + dy * st[1] + dz * st[2];
  const VoxelState* s = grid.states().data();
  int shells = 0;
  std::vector<int64_t> stack;
  for (int64_t i = 0; i < nv; ++i) {
    if (IsOutside(s[i]) || label[static_cast<size_t>(i)] >= 0) continue;
    label[static_cast<size_t>(i)] = shells;
    stack.push_back(i);
    while (!stack.empty()) {
      const int64_t v = stack.back();
      stack.pop_back();
      for (int64_t off : offsets) {
        const int64_t w = v + off;
        if (IsOutside(s[w]) || label[static_cast<size_t>(w)] >= 0) continue;
        label[static_cast<size_t>(w)] = shells;
        stack.push_back(w);
      }
    }
    ++shells;
  }
  return shells;
}

VoxelTopology ComputeVoxelTopology(const VoxelGrid& grid) {
  VoxelTopology topo;
  std::vector<int32_t> label;
  topo.shells = LabelShells(grid, label);
  std::vector<int64_t> chi8(static_cast<size_t>(topo.shells), 0);
  topo.voxels.assign(static_cast<size_t>(topo.shells), 0);
  for (int32_t l : label)
    if (l >= 0) ++topo.voxels[static_cast<size_t>(l)];
  const auto& d = grid.dims();
  const auto st = grid.strides();
  const VoxelState* s = grid.states().data();
  // Lattice vertex (x, y, z) is the corner shared by voxels x-1..x, y-1..y, z-1..z.
  for (int z = 1; z < d[2]; ++z)
    for (int y = 1; y < d[1]; ++y)
      for (int x = 1; x < d[0]; ++x) {
        const int64_t base = grid.Index(x - 1, y - 1, z - 1);
        int m = 0;
        int64_t any = -1;
        for (int b = 0; b < 8; ++b) {
          const int64_t i = base + (b & 1) * st[0] + ((b >> 1) & 1) * st[1] + ((b >> 2) & 1) * st[2];
          if (!IsOutside(s[i])) {
            m |= 1 << b;
            any = i;
          }
        }
        if (m != 0) chi8[static_cast<size_t>(label[static_cast<size_t>(any)])] += kEulerTable[static_cast<size_t>(m)];
      }
  for (int64_t c : chi8) topo.genus.push_back(static_cast<int>(1 - c / 8));

  // Cavities: outside voxels that a 6-flood from the array border does not reach. Border
  // voxels are marked reached and never expanded, so every expanded voxel has all six face
  // neighbours inside the array.
  std::vector<uint8_t> reached(static_cast<size_t>(grid.size()), 0);
  std::vector<int64_t> stack;
  for (int z = 0; z < d[2]; ++z)
    for (int y = 0; y < d[1]; ++y)
      for (int x = 0; x < d[0]; ++x) {
        const int64_t i = grid.Index(x, y, z);
        const bool border = x == 0 || y == 0 || z == 0 || x == d[0] - 1 || y == d[1] - 1 || z == d[2] - 1;
        const bool next_to_border = x == 1 || y == 1 || z == 1 || x == d[0] - 2 || y == d[1] - 2 || z == d[2] - 2;
        if (border) {
          reached[static_cast<size_t>(i)] = 1;
        } else if (next_to_border && IsOutside(s[i])) {
          reached[static_cast<size_t>(i)] = 1;
          stack.push_back(i);
        }
      }
  const int64_t steps[6] = {-st[0], st[0], -st[1], st[1], -st[2], st[2]};
  auto flood = [&]() {
    while (!stack.empty()) {
      const int64_t v = stack.back();
      stack.pop_back();
      for (int64_t step : steps) {
        const int64_t w = v + step;
        if (reached[static_cast<size_t>(w)] || !IsOutside(s[w])) continue;
        reached[static_cast<size_t>(w)] = 1;
        stack.push_back(w);
      }
    }
  };
  flood();
  for (int64_t i = 0; i < grid.size(); ++i) {
    if (!IsOutside(s[i]) || reached[static_cast<size_t>(i)]) continue;
    ++topo.cavities;
    reached[static_cast<size_t>(i)] = 1;
    stack.push_back(i);
    flood();
  }
  return topo;
}

}  // namespace membrane
