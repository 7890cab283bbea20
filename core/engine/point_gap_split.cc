#include "core/engine/point_gap_split.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numeric>

#include "absl/status/status.h"
#include "absl/types/span.h"
#include "core/engine/flat_bitset.h"
#include "core/engine/state_planes.h"

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

constexpr int64_t kCancelPoll = 1 << 16;

// The hard voxels of `grid`, ascending; false when `cancel` fired. Hard voxels are a few
// per thousand of the grid: the states are tested 64 at a time into the words of a block's
// bit-plane, and only the set bits are read.
bool ListHardVoxels(const VoxelGrid& grid, const CancelToken& cancel, std::vector<int64_t>& hard) {
  const absl::Span<const VoxelState> states(grid.states());
  constexpr int64_t kBlock = int64_t{1} << 20;
  FlatBitset plane;
  for (int64_t begin = 0; begin < grid.size(); begin += kBlock) {
    if (cancel.cancelled()) return false;
    const int64_t length = std::min(kBlock, grid.size() - begin);
    plane.EnsureSize(length);
    FillStatePlane(states.subspan(static_cast<size_t>(begin), static_cast<size_t>(length)),
                   StatePredicate::kHard, plane, 0, static_cast<int64_t>(plane.word_count()));
    const uint64_t* words = plane.words();
    for (size_t w = 0; w < plane.word_count(); ++w)
      for (uint64_t bits = words[w]; bits != 0; bits &= bits - 1)
        hard.push_back(begin + static_cast<int64_t>(w) * 64 + std::countr_zero(bits));
  }
  return true;
}

// The voxels of `grid` 26-connected to voxel `start` through hard voxels, breadth first in
// the grid's neighbour order (`seen` marks them).
std::vector<int64_t> BreadthFirst(const VoxelGrid& grid, int64_t start, FlatBitset& seen) {
  const VoxelState* s = grid.states().data();
  std::vector<int64_t> component(1, start);
  seen.set(start);
  for (size_t k = 0; k < component.size(); ++k)
    for (int64_t off : grid.neighbour_offsets()) {
      const int64_t n = component[k] + off;
      if (IsHard(s[n]) && !seen.test(n)) {
        seen.set(n);
        component.push_back(n);
      }
    }
  return component;
}

// The position of voxel `v` in `sorted`, which holds it at `from` or after: galloping from
// `from`, so that ascending look-ups cost the log of each step rather than of the list.
size_t Gallop(const std::vector<int64_t>& sorted, size_t from, int64_t v) {
  size_t lo = from, step = 1;
  while (lo + step < sorted.size() && sorted[lo + step] < v) {
    lo += step;
    step *= 2;
  }
  const size_t hi = std::min(sorted.size(), lo + step + 1);
  const auto begin = sorted.begin() + static_cast<std::ptrdiff_t>(lo);
  const auto end = sorted.begin() + static_cast<std::ptrdiff_t>(hi);
  return static_cast<size_t>(std::lower_bound(begin, end, v) - sorted.begin());
}

// The position of voxel `v` in `sorted`, which holds it.
size_t PositionOf(const std::vector<int64_t>& sorted, int64_t v) {
  return static_cast<size_t>(std::lower_bound(sorted.begin(), sorted.end(), v) - sorted.begin());
}

// Joins the classes of roots `a` and `b` under the lower one, which it returns: the voxels
// joined in index order then hang from a class's first voxel a step or two away, where
// linking the older root under the newer would make a chain of the voxels as they come.
int32_t Link(std::vector<int32_t>& parent, int32_t a, int32_t b) {
  const int32_t root = std::min(a, b);
  parent[std::max(a, b)] = root;
  return root;
}

// Joins the 26-neighbours among the voxels of `hard` (ascending indices of `grid`) when
// near(k, c) holds for their positions k < c, in the order of the offsets; false when `cancel`
// fired. The forward neighbours are the next voxel and four rows of three, whose hard voxels
// are consecutive in `hard`: a cursor per row, moving forward as the voxels do, finds them
// (the grid's states are not read: a state byte a plane ahead is a cache miss per voxel).
template <typename Near>
bool JoinNeighbours(const VoxelGrid& grid, const std::vector<int64_t>& hard,
                    const CancelToken& cancel, std::vector<int32_t>& parent, Near near) {
  const size_t n = hard.size();
  const std::array<int64_t, 3> st = grid.strides();
  // Each row's middle voxel, (dy, dz) = (1, 0), (-1, 1), (0, 1), (1, 1): ascending offsets.
  const std::array<int64_t, 4> rows = {st[1], st[2] - st[1], st[2], st[2] + st[1]};
  std::array<size_t, 4> cursor{};
  for (size_t k = 0; k < n; ++k) {
    if (k % kCancelPoll == 0 && cancel.cancelled()) return false;
    const int64_t v = hard[k];
    int32_t a = Find(parent, static_cast<int32_t>(k));
    auto join = [&](size_t c) {
      const int32_t b = Find(parent, static_cast<int32_t>(c));
      if (a != b && near(k, c)) a = Link(parent, a, b);
    };
    if (k + 1 < n && hard[k + 1] == v + 1) join(k + 1);
    for (size_t r = 0; r < rows.size(); ++r) {
      const int64_t first = v + rows[r] - 1;
      size_t& c = cursor[r];
      while (c < n && hard[c] < first) ++c;
      for (size_t q = c; q < n && hard[q] <= first + 2; ++q) join(q);
    }
  }
  return true;
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

absl::StatusOr<DataPieces> FindDataPieces(const VoxelGrid& grid, const HardVoxelPoints* points,
                                          double reach, double min_fraction,
                                          const CancelToken& cancel) {
  auto cancelled = [] { return absl::CancelledError("reconstruction cancelled"); };
  std::vector<int64_t> hard;
  if (!ListHardVoxels(grid, cancel, hard)) return cancelled();
  if (hard.size() >= static_cast<size_t>(std::numeric_limits<int32_t>::max())) {
    return absl::ResourceExhaustedError("over 2^31 hard voxels: too many to tell pieces apart");
  }
  DataPieces out;
  const size_t n = hard.size();
  if (n == 0) return out;
  out.min_voxels = static_cast<int64_t>(
      std::ceil(std::max(1.0, min_fraction * static_cast<double>(n))));
  const bool by_points = points != nullptr && reach > 0;
  const std::vector<size_t> ranks = by_points ? RanksOf(*points, hard) : std::vector<size_t>();

  // The classes of SplitAtPointGaps's 26-neighbour step over all hard voxels at once (its
  // pairs never leave a component; the classes, not the roots, decide what it returns), or
  // the components themselves without points.
  std::vector<int32_t> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  auto near = [&](size_t k, size_t c) { return Near(*points, hard, ranks, k, c, reach); };
  auto any = [](size_t, size_t) { return true; };
  const bool done = by_points ? JoinNeighbours(grid, hard, cancel, parent, near)
                              : JoinNeighbours(grid, hard, cancel, parent, any);
  if (!done) return cancelled();
  std::vector<int64_t> size(n, 0);
  for (size_t k = 0; k < n; ++k) ++size[Find(parent, static_cast<int32_t>(k))];
  // One class holding all but fewer than min_voxels of the hard voxels: no other class, and
  // no component without it, can be a piece, and its component is not split.
  const int64_t largest = *std::max_element(size.begin(), size.end());
  if (static_cast<int64_t>(n) - largest < out.min_voxels && largest >= out.min_voxels) {
    out.count = 1;
    return out;
  }

  // The 26-components, breadth first from each least voxel in index order (the order the
  // pieces list their voxels in), with each voxel's position in `hard`.
  struct Component {
    std::vector<int64_t> voxels;  // breadth first
    std::vector<int32_t> at;      // their positions in `hard`
    bool split = false;
  };
  std::vector<Component> components;
  std::vector<int32_t> label(n);  // each position's component
  {
    FlatBitset seen(grid.size());
    for (size_t k = 0; k < n; ++k) {
      if (seen.test(hard[k])) continue;
      if (cancel.cancelled()) return cancelled();
      Component& c = components.emplace_back();
      c.voxels = BreadthFirst(grid, hard[k], seen);
      c.at.reserve(c.voxels.size());
      for (int64_t v : c.voxels) {
        c.at.push_back(static_cast<int32_t>(PositionOf(hard, v)));
        label[static_cast<size_t>(c.at.back())] = static_cast<int32_t>(components.size() - 1);
      }
    }
  }
  auto big_component = [&](const Component& c) {
    return static_cast<int64_t>(c.voxels.size()) >= out.min_voxels;
  };

  // A component's classes: split where two hold min_voxels each (SplitAtPointGaps's test),
  // the wider pairs read then around the voxels outside its largest class.
  if (by_points) {
    const int r = static_cast<int>(std::ceil(reach));
    // The rows of the (2r + 1)^3 block around a voxel, as offsets of their middle voxel.
    std::vector<int64_t> rows;
    const std::array<int64_t, 3> st = grid.strides();
    for (int dz = -r; dz <= r; ++dz)
      for (int dy = -r; dy <= r; ++dy) rows.push_back(dy * st[1] + dz * st[2]);
    std::vector<size_t> cursor(rows.size());
    for (size_t ci = 0; ci < components.size(); ++ci) {
      Component& c = components[ci];
      if (!big_component(c)) continue;
      auto big_classes = [&] {
        int big = 0;
        for (int32_t k : c.at) big += parent[k] == k && size[k] >= out.min_voxels;
        return big;
      };
      if (big_classes() < 2) continue;
      if (r > 1) {
        std::vector<int32_t> at;  // c.at ascending: SplitAtPointGaps's `sorted`
        at.reserve(c.at.size());
        for (size_t k = 0; k < n; ++k)
          if (label[k] == static_cast<int32_t>(ci)) at.push_back(static_cast<int32_t>(k));
        int32_t largest_root = at.front();
        for (int32_t k : at)
          if (parent[k] == k && size[k] > size[largest_root]) largest_root = k;
        std::vector<int32_t> others;
        std::vector<bool> other(n, false);
        for (int32_t k : at)
          if (Find(parent, k) != largest_root) {
            others.push_back(k);
            other[static_cast<size_t>(k)] = true;
          }
        // Each pair with a voxel outside the largest class read once (a pair of two such
        // voxels from the lower one), at most r apart along each axis: SplitAtPointGaps's.
        // The hard voxels of one row of the block around a voxel are consecutive in `hard`,
        // and the rows of ascending voxels ascend: each row's are found galloping from where
        // that row's were last, not state by state in the grid.
        std::fill(cursor.begin(), cursor.end(), 0);
        for (int32_t k : others) {
          if (cancel.cancelled()) return cancelled();
          const int64_t v = hard[static_cast<size_t>(k)];
          for (size_t row = 0; row < rows.size(); ++row) {
            const int64_t first = v + rows[row] - r;
            size_t& p = cursor[row];
            p = Gallop(hard, p, first);
            for (size_t q = p; q < n && hard[q] <= first + 2 * r; ++q) {
              if (q == static_cast<size_t>(k) || label[q] != static_cast<int32_t>(ci)) continue;
              if (q < static_cast<size_t>(k) && other[q]) continue;
              const int32_t a = Find(parent, k);
              const int32_t b = Find(parent, static_cast<int32_t>(q));
              if (a == b || !near(static_cast<size_t>(k), q)) continue;
              Link(parent, a, b);
            }
          }
        }
        for (int32_t k : at) size[k] = 0;
        for (int32_t k : at) ++size[Find(parent, k)];
      }
      c.split = big_classes() >= 2;
      out.split = out.split || c.split;
    }
  }

  // Two pieces or more: each in its component's breadth-first order, a split component's
  // big classes numbered in the order their first voxel comes in it.
  for (const Component& c : components)
    if (big_component(c)) out.count += c.split ? 2 : 1;
  if (out.count < 2) return out;
  std::vector<int32_t> part_of_root(by_points ? n : 0, -1);
  for (Component& c : components) {
    if (!big_component(c)) continue;
    if (!c.split) {
      out.pieces.push_back(std::move(c.voxels));
      continue;
    }
    for (size_t i = 0; i < c.voxels.size(); ++i) {
      const int32_t root = Find(parent, c.at[i]);
      if (size[root] < out.min_voxels) continue;
      if (part_of_root[root] < 0) {
        part_of_root[root] = static_cast<int32_t>(out.pieces.size());
        out.pieces.emplace_back();
      }
      out.pieces[static_cast<size_t>(part_of_root[root])].push_back(c.voxels[i]);
    }
  }
  out.count = static_cast<int>(out.pieces.size());
  return out;
}

}  // namespace membrane
