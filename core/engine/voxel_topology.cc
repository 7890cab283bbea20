#include "core/engine/voxel_topology.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <numeric>
#include <utility>
#include <vector>

#include "core/engine/voxel_runs.h"

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

// Adds each lattice vertex's kEulerTable entry to the shell of its incident voxels (all of a
// vertex's non-outside voxels share it, so they are one shell). Only vertices with all 8 voxels
// in the array count. The 4 voxel rows around a line of vertices along x are piecewise constant
// between run ends, so each stretch between two run ends adds one table entry times its length
// and the walk costs O(runs), not O(voxels); inside the solid the stretches are m = 255, which
// adds 0.
void AddEulerCharacteristics(const VoxelRuns& shells, std::vector<int64_t>& chi8) {
  const int nx = shells.dims[0], ny = shells.dims[1], nz = shells.dims[2];
  constexpr int kNone = INT32_MAX;
  for (int z = 1; z < nz; ++z)
    for (int y = 1; y < ny; ++y) {
      // Row k of the four holds voxels (dy, dz) = (k & 1, k >> 1); in a vertex configuration its
      // voxel x - 1 is bit 2k and its voxel x is bit 2k + 1.
      int64_t next[4], last[4];
      bool active[4] = {false, false, false, false};
      for (int k = 0; k < 4; ++k) {
        const int64_t r = shells.Row(y - 1 + (k & 1), z - 1 + (k >> 1));
        next[k] = shells.row_begin[static_cast<size_t>(r)];
        last[k] = shells.row_begin[static_cast<size_t>(r) + 1];
      }
      if (next[0] == last[0] && next[1] == last[1] && next[2] == last[2] && next[3] == last[3]) continue;
      int column = 0;   // 4-bit occupancy at voxel x, bit 2k for row k
      int shell = -1;   // shell of the voxels in `column`, or of the last nonempty one
      int from = 0;     // `column` holds on voxels [from, x)
      for (;;) {
        int x = kNone;
        for (int k = 0; k < 4; ++k) {
          if (next[k] == last[k]) continue;
          const VoxelRun& run = shells.runs[static_cast<size_t>(next[k])];
          x = std::min(x, active[k] ? run.end : run.begin);
        }
        if (x == kNone) break;
        if (column != 0) {
          // Vertices strictly inside [from, x) see `column` on both sides.
          const int lo = std::max(from + 1, 1), hi = std::min(x - 1, nx - 1);
          if (lo <= hi) {
            chi8[static_cast<size_t>(shell)] +=
                static_cast<int64_t>(hi - lo + 1) * kEulerTable[static_cast<size_t>(column | column << 1)];
          }
        }
        int after = 0;
        for (int k = 0; k < 4; ++k) {
          if (next[k] == last[k]) continue;
          const VoxelRun& run = shells.runs[static_cast<size_t>(next[k])];
          if (active[k] && run.end == x) {
            active[k] = false;
            ++next[k];
          } else if (!active[k] && run.begin == x) {
            active[k] = true;
          }
          if (active[k]) {
            after |= 1 << (2 * k);
            shell = run.component;
          }
        }
        // Vertex x sees `column` at voxel x - 1 and `after` at voxel x.
        if (x >= 1 && x <= nx - 1) {
          chi8[static_cast<size_t>(shell)] += kEulerTable[static_cast<size_t>(column | after << 1)];
        }
        column = after;
        from = x;
      }
    }
}

// Outside components not reaching the array border. Matches a 6-flood seeded from the outside
// voxels next to the border layer that never enters the border layer: components of outside
// voxels off the border, those with a voxel next to the border layer not counted.
int CountCavities(const VoxelRuns& shells) {
  VoxelRuns outside = OutsideRunsOffBorder(shells);
  const int components = LabelRunComponents(outside, RunAdjacency::kFace);
  const int nx = outside.dims[0], ny = outside.dims[1], nz = outside.dims[2];
  std::vector<uint8_t> open(static_cast<size_t>(components), 0);
  for (int z = 1; z < nz - 1; ++z)
    for (int y = 1; y < ny - 1; ++y) {
      const int64_t r = outside.Row(y, z);
      const bool edge_row = y == 1 || z == 1 || y == ny - 2 || z == nz - 2;
      for (int64_t i = outside.row_begin[static_cast<size_t>(r)]; i < outside.row_begin[static_cast<size_t>(r) + 1];
           ++i) {
        const VoxelRun& run = outside.runs[static_cast<size_t>(i)];
        if (edge_row || run.begin == 1 || run.end == nx - 1) open[static_cast<size_t>(run.component)] = 1;
      }
    }
  int cavities = 0;
  for (uint8_t o : open) cavities += o == 0;
  return cavities;
}

}  // namespace

int LabelShells(const VoxelGrid& grid, std::vector<int32_t>& label) {
  VoxelRuns shells = NonOutsideRuns(grid);
  const int count = LabelRunComponents(shells, RunAdjacency::kVertex);
  label.assign(static_cast<size_t>(grid.size()), -1);
  for (int64_t r = 0; r < shells.rows(); ++r) {
    const int64_t row = r * shells.dims[0];
    for (int64_t i = shells.row_begin[static_cast<size_t>(r)]; i < shells.row_begin[static_cast<size_t>(r) + 1]; ++i) {
      const VoxelRun& run = shells.runs[static_cast<size_t>(i)];
      std::fill(label.begin() + row + run.begin, label.begin() + row + run.end, run.component);
    }
  }
  return count;
}

VoxelTopology ComputeVoxelTopology(const VoxelGrid& grid) {
  return *ComputeVoxelTopology(grid, CancelToken::Never());
}

std::optional<VoxelTopology> ComputeVoxelTopology(const VoxelGrid& grid,
                                                  const CancelToken& cancel) {
  return ComputeVoxelTopology(grid, cancel, 1);
}

std::optional<VoxelTopology> ComputeVoxelTopology(const VoxelGrid& grid,
                                                  const CancelToken& cancel, int threads) {
  VoxelTopology topo;
  VoxelRuns shells = NonOutsideRuns(grid, threads);
  if (cancel.cancelled()) return std::nullopt;
  topo.shells = LabelRunComponents(shells, RunAdjacency::kVertex);
  if (cancel.cancelled()) return std::nullopt;
  topo.voxels.assign(static_cast<size_t>(topo.shells), 0);
  for (const VoxelRun& run : shells.runs) topo.voxels[static_cast<size_t>(run.component)] += run.end - run.begin;
  std::vector<int64_t> chi8(static_cast<size_t>(topo.shells), 0);
  AddEulerCharacteristics(shells, chi8);
  if (cancel.cancelled()) return std::nullopt;
  for (int64_t c : chi8) topo.genus.push_back(static_cast<int>(1 - c / 8));
  topo.cavities = CountCavities(shells);
  return topo;
}

CarveTopologyChange CountCarveLocally(const VoxelGrid& grid, absl::Span<const int64_t> carved,
                                      int margin) {
  CarveTopologyChange change;
  const VoxelState* s = grid.states().data();
  std::vector<int64_t> sorted(carved.begin(), carved.end());
  std::sort(sorted.begin(), sorted.end());
  auto is_carved = [&](int64_t i) { return std::binary_search(sorted.begin(), sorted.end(), i); };
  auto solid_after = [&](int64_t i) { return !IsOutside(s[i]) && !is_carved(i); };

  // Euler characteristic: only the corners of the carved voxels see another configuration.
  // Vertex v's configuration holds voxel v - 1 + d at bit d.x + 2 d.y + 4 d.z.
  const auto st = grid.strides();
  std::vector<int64_t> corners;  // the voxel index of each vertex's voxel (v - 1) + (1, 1, 1)
  for (int64_t c : sorted)
    for (int k = 0; k < 8; ++k) corners.push_back(c + (k & 1) * st[0] + (k >> 1 & 1) * st[1] + (k >> 2) * st[2]);
  std::sort(corners.begin(), corners.end());
  corners.erase(std::unique(corners.begin(), corners.end()), corners.end());
  int64_t chi8 = 0;
  for (int64_t v : corners) {
    int before = 0, after = 0;
    for (int b = 0; b < 8; ++b) {
      const int64_t i = v - (1 - (b & 1)) * st[0] - (1 - (b >> 1 & 1)) * st[1] - (1 - (b >> 2)) * st[2];
      if (!IsOutside(s[i])) before |= 1 << b;
      if (solid_after(i)) after |= 1 << b;
    }
    chi8 += kEulerTable[static_cast<size_t>(after)] - kEulerTable[static_cast<size_t>(before)];
  }
  change.euler_change = chi8 / 8;

  // The solid voxels beside the carved ones, and the carved voxels' outside face neighbours.
  const std::array<int64_t, 27>& block = grid.block_offsets();
  std::vector<int64_t> rim;
  Coord lo = grid.CoordOf(sorted.front()), hi = lo;
  for (int64_t c : sorted) {
    const Coord q = grid.CoordOf(c);
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::min(lo[a], q[a]);
      hi[a] = std::max(hi[a], q[a]);
    }
    for (int k = 0; k < 27; ++k) {
      const int64_t n = c + block[static_cast<size_t>(k)];
      if (IsFaceStep(k) && IsOutside(s[n])) change.touches_outside = true;
      if (solid_after(n)) rim.push_back(n);
    }
  }
  if (rim.empty()) {
    change.shells = CarveTopologyChange::Shells::kRemoved;
    return change;
  }
  std::sort(rim.begin(), rim.end());
  rim.erase(std::unique(rim.begin(), rim.end()), rim.end());

  // A 26-flood of the solid left, inside the box (the rim and `margin` voxels beyond it), from
  // one rim voxel: the shell stays one when it reaches every rim voxel (each voxel of the shell
  // reaches the carved ones through a rim voxel), and may split otherwise.
  for (int a = 0; a < 3; ++a) {
    lo[a] = std::max(lo[a] - 1 - margin, 0);
    hi[a] = std::min(hi[a] + 1 + margin, grid.dim(a) - 1);
  }
  const int bx = hi.x - lo.x + 1, by = hi.y - lo.y + 1, bz = hi.z - lo.z + 1;
  auto box_index = [&](const Coord& q) {
    return (static_cast<int64_t>(q.z - lo.z) * by + (q.y - lo.y)) * bx + (q.x - lo.x);
  };
  std::vector<uint8_t> reached(static_cast<size_t>(bx) * by * bz, 0);
  std::vector<Coord> stack = {grid.CoordOf(rim.front())};
  reached[static_cast<size_t>(box_index(stack.front()))] = 1;
  size_t rim_reached = 0;
  while (!stack.empty()) {
    const Coord q = stack.back();
    stack.pop_back();
    if (std::binary_search(rim.begin(), rim.end(), grid.Index(q))) ++rim_reached;
    for (const Coord& d : kBlockSteps) {
      const Coord n{q.x + d.x, q.y + d.y, q.z + d.z};
      if (n.x < lo.x || n.y < lo.y || n.z < lo.z || n.x > hi.x || n.y > hi.y || n.z > hi.z) continue;
      uint8_t& r = reached[static_cast<size_t>(box_index(n))];
      if (r != 0 || !solid_after(grid.Index(n))) continue;
      r = 1;
      stack.push_back(n);
    }
  }
  change.shells = rim_reached == rim.size() ? CarveTopologyChange::Shells::kKept
                                             : CarveTopologyChange::Shells::kUnknown;
  return change;
}

int TotalGenus(const VoxelTopology& t) {
  return std::accumulate(t.genus.begin(), t.genus.end(), 0);
}

}  // namespace membrane
