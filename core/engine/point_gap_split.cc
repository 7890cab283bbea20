#include "core/engine/point_gap_split.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <numeric>

#include "absl/types/span.h"

namespace membrane {
namespace {

int32_t Find(std::vector<int32_t>& parent, int32_t i) {
  while (parent[i] != i) {
    parent[i] = parent[parent[i]];
    i = parent[i];
  }
  return i;
}

// The forward offsets (above 0: each pair once) to the voxels at most `r` apart along each
// axis.
std::vector<int64_t> ForwardOffsets(const VoxelGrid& grid, int r) {
  std::vector<int64_t> offsets;
  const int64_t centre = grid.Index(Coord{r, r, r});
  for (int dz = -r; dz <= r; ++dz)
    for (int dy = -r; dy <= r; ++dy)
      for (int dx = -r; dx <= r; ++dx) {
        const int64_t off = grid.Index(Coord{r + dx, r + dy, r + dz}) - centre;
        if (off > 0) offsets.push_back(off);
      }
  return offsets;
}

// The ranks (HardVoxelPoints::voxels) of `sorted`'s voxels, ascending grid indices that all
// hold points: one merge of the two lists.
std::vector<size_t> RanksOf(const HardVoxelPoints& points, const std::vector<int64_t>& sorted) {
  const absl::Span<const int64_t> all = points.voxels();
  std::vector<size_t> ranks(sorted.size());
  size_t r = 0;
  for (size_t k = 0; k < sorted.size(); ++k) {
    while (r < all.size() && all[r] < sorted[k]) ++r;
    ranks[k] = r;
  }
  return ranks;
}

// Whether the points of `sorted`'s voxels k and c come within `reach` (false when one holds
// none, as a hard voxel made by no point would).
bool Near(const HardVoxelPoints& points, const std::vector<int64_t>& sorted,
          const std::vector<size_t>& ranks, size_t k, size_t c, double reach) {
  const absl::Span<const int64_t> all = points.voxels();
  if (ranks[k] >= all.size() || all[ranks[k]] != sorted[k]) return false;
  if (ranks[c] >= all.size() || all[ranks[c]] != sorted[c]) return false;
  return points.PointsWithin(ranks[k], ranks[c], reach);
}

// Joins the voxels of `sorted` (ascending grid indices) that lie `offsets` apart and whose
// points come within `reach`. Each offset's partner is found by a cursor that only moves
// forward, as the voxels do: no search.
void JoinAlong(const VoxelGrid& grid, const HardVoxelPoints& points,
               const std::vector<int64_t>& sorted, const std::vector<size_t>& ranks,
               const std::vector<int64_t>& offsets, double reach, std::vector<int32_t>& parent) {
  const VoxelState* s = grid.states().data();
  const int64_t voxels = grid.size();
  std::vector<size_t> cursor(offsets.size(), 0);
  for (size_t k = 0; k < sorted.size(); ++k) {
    const int64_t v = sorted[k];
    for (size_t o = 0; o < offsets.size(); ++o) {
      const int64_t n = v + offsets[o];
      if (n >= voxels || !IsHard(s[n])) continue;
      size_t& c = cursor[o];
      while (c < sorted.size() && sorted[c] < n) ++c;
      if (c == sorted.size() || sorted[c] != n) continue;
      const int32_t a = Find(parent, static_cast<int32_t>(k));
      const int32_t b = Find(parent, static_cast<int32_t>(c));
      if (a == b || !Near(points, sorted, ranks, k, c, reach)) continue;
      parent[a] = b;
    }
  }
}

// Joins the voxels of `sorted` outside the largest class of `parent` to every voxel of
// `sorted` `offsets` apart, before or after, whose points come within `reach`: every pair
// with a voxel outside that class is read, and the pairs inside it are joined already, so the
// classes come out as from every pair, at the cost of the voxels outside the largest class.
void JoinOutsideLargest(const VoxelGrid& grid, const HardVoxelPoints& points,
                        const std::vector<int64_t>& sorted, const std::vector<size_t>& ranks,
                        const std::vector<int64_t>& offsets, double reach,
                        const std::vector<int64_t>& size, std::vector<int32_t>& parent) {
  const int32_t largest = static_cast<int32_t>(std::max_element(size.begin(), size.end()) -
                                               size.begin());
  std::vector<int32_t> others;
  for (size_t k = 0; k < sorted.size(); ++k)
    if (Find(parent, static_cast<int32_t>(k)) != largest) others.push_back(static_cast<int32_t>(k));
  const VoxelState* s = grid.states().data();
  const int64_t voxels = grid.size();
  for (int32_t k : others) {
    const int64_t v = sorted[static_cast<size_t>(k)];
    for (int64_t off : offsets)
      for (int64_t n : {v - off, v + off}) {
        if (n < 0 || n >= voxels || !IsHard(s[n])) continue;
        const auto it = std::lower_bound(sorted.begin(), sorted.end(), n);
        if (it == sorted.end() || *it != n) continue;
        const size_t c = static_cast<size_t>(it - sorted.begin());
        const int32_t a = Find(parent, k);
        const int32_t b = Find(parent, static_cast<int32_t>(c));
        if (a == b || !Near(points, sorted, ranks, static_cast<size_t>(k), c, reach)) continue;
        parent[a] = b;
      }
  }
}

// The number of classes of `parent` holding at least `min_voxels`; `size` gets each root's
// class size (0 for the others).
int BigClasses(std::vector<int32_t>& parent, int64_t min_voxels, std::vector<int64_t>& size) {
  size.assign(parent.size(), 0);
  for (size_t k = 0; k < parent.size(); ++k) ++size[Find(parent, static_cast<int32_t>(k))];
  int big = 0;
  for (size_t k = 0; k < parent.size(); ++k)
    big += parent[k] == static_cast<int32_t>(k) && size[k] >= min_voxels;
  return big;
}

}  // namespace

std::vector<std::vector<int64_t>> SplitAtPointGaps(const VoxelGrid& grid,
                                                   const HardVoxelPoints& points,
                                                   const std::vector<int64_t>& component,
                                                   double reach, int64_t min_voxels) {
  std::vector<int64_t> sorted = component;
  std::sort(sorted.begin(), sorted.end());
  std::vector<int32_t> parent(sorted.size());
  std::iota(parent.begin(), parent.end(), 0);
  std::vector<int64_t> size;
  // The 26-neighbours join almost every surface; the wider pairs are read only when that
  // leaves two big parts, and only around the voxels outside the largest. Points within
  // `reach` lie in voxels at most ceil(reach) apart along each axis.
  const std::vector<size_t> ranks = RanksOf(points, sorted);
  JoinAlong(grid, points, sorted, ranks, ForwardOffsets(grid, 1), reach, parent);
  if (BigClasses(parent, min_voxels, size) < 2) return {component};
  const int r = static_cast<int>(std::ceil(reach));
  if (r > 1) {
    JoinOutsideLargest(grid, points, sorted, ranks, ForwardOffsets(grid, r), reach, size,
                       parent);
  }
  if (BigClasses(parent, min_voxels, size) < 2) return {component};
  // The big parts, numbered in the order their first voxel comes in the component.
  std::vector<int32_t> part_of_root(sorted.size(), -1);
  int32_t parts = 0;
  std::vector<int32_t> part_of_voxel(component.size());
  for (size_t k = 0; k < component.size(); ++k) {
    const size_t at = static_cast<size_t>(
        std::lower_bound(sorted.begin(), sorted.end(), component[k]) - sorted.begin());
    const int32_t root = Find(parent, static_cast<int32_t>(at));
    if (size[root] >= min_voxels && part_of_root[root] < 0) part_of_root[root] = parts++;
    part_of_voxel[k] = part_of_root[root];
  }
  std::vector<std::vector<int64_t>> out(static_cast<size_t>(parts));
  for (size_t k = 0; k < component.size(); ++k)
    if (part_of_voxel[k] >= 0) out[static_cast<size_t>(part_of_voxel[k])].push_back(component[k]);
  return out;
}

}  // namespace membrane
