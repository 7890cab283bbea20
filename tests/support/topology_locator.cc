#include "tests/support/topology_locator.h"

#include <algorithm>
#include <cstdint>
#include <deque>
#include <map>
#include <utility>
#include <vector>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "core/engine/local_topology.h"
#include "core/engine/voxel_state.h"
#include "core/engine/voxel_topology.h"

namespace membrane::testing {
namespace {

std::string Where(const VoxelGrid& grid, int64_t index) {
  const Coord c = grid.CoordOf(index);
  const double l = grid.voxel_size();
  return absl::StrFormat("(%d, %d, %d) at model (%.6g, %.6g, %.6g)", c.x, c.y, c.z,
                         grid.origin()[0] + (c.x + 0.5) * l, grid.origin()[1] + (c.y + 0.5) * l,
                         grid.origin()[2] + (c.z + 0.5) * l);
}

uint32_t SolidMask(const VoxelGrid& grid, const std::vector<uint8_t>& solid, int64_t index) {
  const std::array<int64_t, 27>& offsets = grid.block_offsets();
  uint32_t mask = 0;
  for (int k = 0; k < 27; ++k)
    if (solid[index + offsets[k]]) mask |= 1u << k;
  return mask;
}

// Removes simple voxels of `solid` (26,6) until none is left, peeling from the outside in:
// what remains of a shell of genus g is a thin set with g independent loops.
void ThinHomotopically(const VoxelGrid& grid, std::vector<uint8_t>& solid) {
  const auto& nb = grid.neighbour_offsets();
  std::vector<uint8_t> queued(solid.size(), 0);
  std::deque<int64_t> queue;
  for (int64_t i = 0; i < grid.size(); ++i) {
    if (solid[i] && !IsInside(grid.at(i))) {
      queue.push_back(i);
      queued[i] = 1;
    }
  }
  while (!queue.empty()) {
    const int64_t v = queue.front();
    queue.pop_front();
    queued[v] = 0;
    if (!solid[v] || !IsSimple(SolidMask(grid, solid, v))) continue;
    solid[v] = 0;
    for (int64_t o : nb) {
      if (solid[v + o] && !queued[v + o]) {
        queued[v + o] = 1;
        queue.push_back(v + o);
      }
    }
  }
}

struct Arc {
  int shell;
  std::vector<int64_t> voxels;
};

// The arcs of the thinned set: its 26-components once the voxels with three or more thinned
// neighbours (junctions) are set aside.
std::vector<Arc> ArcsOf(const VoxelGrid& grid, const std::vector<uint8_t>& thin,
                        const std::vector<int32_t>& shell) {
  const auto& nb = grid.neighbour_offsets();
  std::vector<uint8_t> arc(thin.size(), 0);
  for (int64_t i = 0; i < grid.size(); ++i) {
    if (!thin[i]) continue;
    int n = 0;
    for (int64_t o : nb) n += thin[i + o];
    arc[i] = n <= 2;
  }
  std::vector<Arc> arcs;
  for (int64_t i = 0; i < grid.size(); ++i) {
    if (!arc[i]) continue;
    Arc a{shell[i], {i}};
    arc[i] = 0;
    for (size_t k = 0; k < a.voxels.size(); ++k) {
      for (int64_t o : nb) {
        const int64_t w = a.voxels[k] + o;
        if (arc[w]) {
          arc[w] = 0;
          a.voxels.push_back(w);
        }
      }
    }
    arcs.push_back(std::move(a));
  }
  return arcs;
}

int64_t NearestToCentroid(const VoxelGrid& grid, const std::vector<int64_t>& voxels) {
  double sum[3] = {0, 0, 0};
  for (int64_t v : voxels) {
    const Coord c = grid.CoordOf(v);
    for (int d = 0; d < 3; ++d) sum[d] += c[d];
  }
  int64_t best = voxels.front();
  double best_d = 1e300;
  for (int64_t v : voxels) {
    const Coord c = grid.CoordOf(v);
    double d2 = 0;
    for (int d = 0; d < 3; ++d) {
      const double e = c[d] - sum[d] / voxels.size();
      d2 += e * e;
    }
    if (d2 < best_d) {
      best_d = d2;
      best = v;
    }
  }
  return best;
}

void AppendLoops(const VoxelGrid& grid, const VoxelTopology& topo,
                 const std::vector<int32_t>& shell, int max_items, std::string& out) {
  std::vector<uint8_t> solid(grid.size());
  for (int64_t i = 0; i < grid.size(); ++i) solid[i] = !IsOutside(grid.at(i));
  ThinHomotopically(grid, solid);
  std::vector<Arc> arcs = ArcsOf(grid, solid, shell);
  std::stable_sort(arcs.begin(), arcs.end(), [](const Arc& a, const Arc& b) {
    return a.shell != b.shell ? a.shell < b.shell : a.voxels.size() > b.voxels.size();
  });
  for (int s = 0; s < topo.shells; ++s) {
    if (topo.genus[s] == 0) continue;
    absl::StrAppend(&out, "shell ", s, " (genus ", topo.genus[s], ", ", topo.voxels[s],
                    " voxels): loop arcs after thinning:");
    int shown = 0;
    for (const Arc& a : arcs) {
      if (a.shell != s || a.voxels.size() < 2) continue;
      if (shown++ == max_items) {
        absl::StrAppend(&out, " ...");
        break;
      }
      absl::StrAppend(&out, "\n  ", a.voxels.size(), " voxels around ",
                      Where(grid, NearestToCentroid(grid, a.voxels)));
    }
    if (shown == 0) absl::StrAppend(&out, " none (the thinned set is all junctions)");
    absl::StrAppend(&out, "\n");
  }
}

void AppendContacts(const VoxelGrid& grid, const std::vector<int32_t>& shell, int max_items,
                    std::string& out) {
  const auto& nb = grid.neighbour_offsets();
  // 26-components of the hard voxels.
  std::vector<int32_t> owner(grid.size(), -1);
  std::vector<int64_t> sizes;
  int64_t hard = 0;
  for (int64_t i = 0; i < grid.size(); ++i) hard += IsHard(grid.at(i));
  std::vector<int64_t> stack;
  for (int64_t i = 0; i < grid.size(); ++i) {
    if (!IsHard(grid.at(i)) || owner[i] >= 0) continue;
    const int32_t c = static_cast<int32_t>(sizes.size());
    int64_t n = 0;
    owner[i] = c;
    stack.push_back(i);
    while (!stack.empty()) {
      const int64_t v = stack.back();
      stack.pop_back();
      ++n;
      for (int64_t o : nb) {
        if (IsHard(grid.at(v + o)) && owner[v + o] < 0) {
          owner[v + o] = c;
          stack.push_back(v + o);
        }
      }
    }
    sizes.push_back(n);
  }
  // Only the large components grow; the others are set free.
  const int64_t large = std::max<int64_t>(50, hard / 100);
  std::deque<int64_t> queue;
  for (int64_t i = 0; i < grid.size(); ++i) {
    if (owner[i] < 0) continue;
    if (sizes[owner[i]] < large) {
      owner[i] = -1;
    } else {
      queue.push_back(i);
    }
  }
  std::map<std::pair<int32_t, int32_t>, int64_t> contacts;  // first meeting per pair
  while (!queue.empty()) {
    const int64_t v = queue.front();
    queue.pop_front();
    for (int64_t o : nb) {
      const int64_t w = v + o;
      if (IsOutside(grid.at(w))) continue;
      if (owner[w] < 0) {
        owner[w] = owner[v];
        queue.push_back(w);
      } else if (owner[w] != owner[v]) {
        contacts.emplace(std::minmax(owner[v], owner[w]), v);
      }
    }
  }
  int shown = 0;
  for (const auto& [pair, v] : contacts) {
    if (shown++ == max_items) {
      absl::StrAppend(&out, "  ... ", contacts.size() - max_items, " more contacts\n");
      break;
    }
    absl::StrAppend(&out, "shell ", shell[v], ": data components of ", sizes[pair.first],
                    " and ", sizes[pair.second], " hard voxels meet at ", Where(grid, v), "\n");
  }
}

}  // namespace

std::string LocateHandlesAndContacts(const VoxelGrid& grid, int max_items) {
  const VoxelTopology topo = ComputeVoxelTopology(grid);
  std::vector<int32_t> shell;
  LabelShells(grid, shell);
  std::string out;
  AppendLoops(grid, topo, shell, max_items, out);
  AppendContacts(grid, shell, max_items, out);
  return out;
}

}  // namespace membrane::testing
