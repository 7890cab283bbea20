#include "core/mesh/diagonal_bridging.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include "core/base/parallel_tasks.h"
#include "core/engine/local_topology.h"
#include "core/engine/voxel_state_words.h"

namespace membrane {
namespace {

bool Solid(VoxelState s) { return !IsOutside(s); }

// False only when none of the 8 voxels from index i on (along x) passes the three-load test of
// ForEachCornerContact (solid, +z outside, not solid on both sides along x, nor along y); the
// voxels and their face neighbours must exist. Outside is the top bit of a state.
bool AnyContactCandidate(const VoxelGrid& grid, int64_t i, const std::array<int64_t, 3>& st) {
  const VoxelState* s = grid.states().data() + i;
  auto solid = [&](int64_t offset) {  // top bit of each byte set where solid
    return ~LoadStates8(s + offset) & kOutsideBits8;
  };
  const uint64_t candidate = solid(0) & ~solid(st[2]) & ~(solid(-st[0]) & solid(st[0])) &
                             ~(solid(-st[1]) & solid(st[1]));
  return (candidate & kOutsideBits8) != 0;
}

// Calls fn(others) for every corner-only contact of voxel i with a voxel one plane up, where
// `others` are the indices of the 6 other voxels of its 2x2x2 block in increasing order;
// returns how many. Each contact is seen once, from its voxel with the lower z.
template <typename Fn>
int64_t ContactsAt(const VoxelGrid& grid, int64_t i, const std::array<int64_t, 3>& st, Fn fn) {
  if (!Solid(grid.at(i))) return 0;
  // The voxel's face neighbours toward its partner (+z, and one side along x and y) are
  // outside in a contact: most voxels are ruled out by three loads.
  if (Solid(grid.at(i + st[2])) || (Solid(grid.at(i - st[0])) && Solid(grid.at(i + st[0]))) ||
      (Solid(grid.at(i - st[1])) && Solid(grid.at(i + st[1]))))
    return 0;
  int64_t contacts = 0;
  for (int sy = -1; sy <= 1; sy += 2)
    for (int sx = -1; sx <= 1; sx += 2) {
      const std::array<int64_t, 3> step = {sx * st[0], sy * st[1], st[2]};
      if (!Solid(grid.at(i + step[0] + step[1] + step[2]))) continue;
      std::array<int64_t, 6> others{};
      bool contact = true;
      for (int o = 1; o < 7; ++o) {
        const int64_t j =
            i + ((o & 1) ? step[0] : 0) + ((o & 2) ? step[1] : 0) + ((o & 4) ? step[2] : 0);
        others[o - 1] = j;
        if (Solid(grid.at(j))) contact = false;
      }
      if (!contact) continue;
      ++contacts;
      std::sort(others.begin(), others.end());
      fn(others);
    }
  return contacts;
}

// Calls visit(i) for the voxels of row (y, z) from x on, but for runs of eight that
// AnyContactCandidate rules out (nearly everywhere).
template <typename Visit>
void ScanRow(const VoxelGrid& grid, int y, int z, int x, const std::array<int64_t, 3>& st,
             Visit visit) {
  const int nx = grid.dim(0);
  for (; x < nx - 1; ++x) {
    const int64_t i = grid.Index(x, y, z);
    if ((x - 1) % 8 == 0 && x + 8 <= nx - 1 && !AnyContactCandidate(grid, i, st)) {
      x += 7;
      continue;
    }
    visit(i);
  }
}

// Calls fn(others) for every corner-only contact in index order (ContactsAt) and returns how
// many; changed() says whether fn has changed the grid. Until it has, the grid is as it was:
// the voxels with a contact are found first, a z plane a task on `threads`, and visited in
// order; from the first change on, every voxel after it is visited in turn. The same calls and
// count for any thread count.
template <typename Fn, typename Changed>
int64_t ForEachCornerContact(const VoxelGrid& grid, Fn fn, Changed changed, int threads) {
  const auto st = grid.strides();
  const auto& d = grid.dims();
  std::vector<std::vector<int64_t>> found(static_cast<size_t>(std::max(d[2], 2)));
  RunTasks(std::max(threads, 1), d[2] > 2 ? d[2] - 2 : 0, [&](int, int64_t task) {
    const int z = static_cast<int>(task) + 1;
    for (int y = 1; y < d[1] - 1; ++y) {
      ScanRow(grid, y, z, 1, st, [&](int64_t i) {
        if (ContactsAt(grid, i, st, [](const std::array<int64_t, 6>&) {}) > 0) {
          found[static_cast<size_t>(z)].push_back(i);
        }
      });
    }
  });
  int64_t contacts = 0, changed_after = -1;
  for (const std::vector<int64_t>& plane : found) {
    for (int64_t i : plane) {
      contacts += ContactsAt(grid, i, st, fn);
      if (changed()) {
        changed_after = i + 1;
        break;
      }
    }
    if (changed_after >= 0) break;
  }
  if (changed_after < 0) return contacts;
  const Coord from = grid.CoordOf(changed_after);
  for (int z = std::max(from.z, 1); z < d[2] - 1; ++z)
    for (int y = z == from.z ? std::max(from.y, 1) : 1; y < d[1] - 1; ++y) {
      ScanRow(grid, y, z, z == from.z && y == from.y ? std::max(from.x, 1) : 1, st,
              [&](int64_t i) { contacts += ContactsAt(grid, i, st, fn); });
    }
  return contacts;
}

}  // namespace

BridgingResult BridgeDiagonalContacts(VoxelGrid& grid, int max_scans, int threads) {
  BridgingResult result;
  for (int scan = 0; scan < max_scans; ++scan) {
    const int64_t before = result.added;
    const int64_t contacts = ForEachCornerContact(
        grid,
        [&](const std::array<int64_t, 6>& others) {
          for (int64_t j : others) {
            // An earlier bridge in this scan may already have joined this contact.
            if (Solid(grid.at(j))) return;
          }
          for (int64_t j : others) {
            if (grid.OnArrayBorder(grid.CoordOf(j))) continue;
            if (!IsSimple(NeighbourhoodMask(grid, j, Solid))) continue;
            grid.set(j, kBoundarySoft);
            ++result.added;
            return;
          }
        },
        [&] { return result.added != before; }, threads);
    // A scan that bridged nothing left the grid as it found it: its count is what is left,
    // without a scan more of the whole grid.
    if (contacts == 0 || result.added == before) {
      result.remaining = contacts;
      return result;
    }
  }
  result.remaining = ForEachCornerContact(
      grid, [](const std::array<int64_t, 6>&) {}, [] { return false; }, threads);
  return result;
}

}  // namespace membrane
