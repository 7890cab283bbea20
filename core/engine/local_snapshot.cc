#include "core/engine/local_snapshot.h"

#include <algorithm>
#include <bit>
#include <cstring>

#include "absl/types/span.h"
#include "core/base/parallel_tasks.h"
#include "core/base/split_sort.h"
#include "core/engine/interior_plane.h"
#include "core/engine/state_planes.h"
#include "core/engine/voxel_state.h"

namespace membrane {
namespace {

// Fewer bricks than this are computed on the calling thread: starting threads would cost more
// than the bricks (a brick's box is some 40^3 voxels).
constexpr int64_t kMinBricksToSplit = 16;

}  // namespace

std::optional<std::vector<int64_t>> LocalSnapshot::Take(int n, const std::vector<VoxelBox>& written,
                                                        const LocalSnapshotOptions& options,
                                                        const CancelToken& cancel) {
  // The bricks' packed anchors are kept (resized below) and reassigned: their buffers serve
  // again without allocations, a few thousand a pass.
  slot_.clear();
  if (options.max_share <= 0 || options.brick < 1) {
    Release();
    return std::nullopt;
  }
  n_ = n;
  brick_ = options.brick;
  const std::array<int, 3>& dims = grid_.dims();
  for (int d = 0; d < 3; ++d) brick_counts_[d] = (dims[d] + brick_ - 1) / brick_;
  slot_.assign(static_cast<size_t>(brick_counts_[0]) * brick_counts_[1] * brick_counts_[2], -1);
  // The bricks within 2n + 1 of a written voxel, in increasing brick index.
  const int reach = 2 * n + 1;
  std::vector<int64_t> marked;
  for (const VoxelBox& box : written) {
    if (box.empty()) continue;
    int b_lo[3], b_hi[3];
    for (int d = 0; d < 3; ++d) {
      b_lo[d] = std::max(box.lo[d] - reach, 0) / brick_;
      b_hi[d] = std::min(box.hi[d] + reach, dims[d] - 1) / brick_;
    }
    for (int bz = b_lo[2]; bz <= b_hi[2]; ++bz)
      for (int by = b_lo[1]; by <= b_hi[1]; ++by)
        for (int bx = b_lo[0]; bx <= b_hi[0]; ++bx) {
          const int64_t b = BrickIndex(bx, by, bz);
          if (slot_[static_cast<size_t>(b)] < 0) {
            slot_[static_cast<size_t>(b)] = 0;
            marked.push_back(b);
          }
        }
  }
  std::sort(marked.begin(), marked.end());
  const int64_t side = brick_ + 2 * (n + 2);
  if (static_cast<double>(marked.size()) * static_cast<double>(side * side * side) >
      options.max_share * static_cast<double>(grid_.size())) {
    Release();
    return std::nullopt;
  }
  bricks_.resize(marked.size());
  for (size_t k = 0; k < marked.size(); ++k) {
    slot_[static_cast<size_t>(marked[k])] = static_cast<int32_t>(k);
  }
  // A range of bricks a task, a few ranges a thread so that ranges of busy bricks even out;
  // each brick reads the grid and writes only its own planes and its range's candidates,
  // which are joined in range order and sorted: the same list for any thread count.
  const int threads = static_cast<int>(work_.size());
  const TaskRanges ranges =
      TaskRanges::Split(static_cast<int64_t>(marked.size()), threads, 8, kMinBricksToSplit);
  std::vector<std::vector<int64_t>> found(static_cast<size_t>(ranges.tasks));
  TaskCancel stop(cancel, threads, /*period=*/1);
  RunTasks(threads, ranges.tasks, [&](int worker, int64_t task) {
    for (int64_t k = ranges.begin(task); k < ranges.end(task); ++k) {
      if (stop.Poll(worker)) return;
      const int64_t b = marked[static_cast<size_t>(k)];
      const Coord core_lo{
          static_cast<int>(b % brick_counts_[0]) * brick_,
          static_cast<int>((b / brick_counts_[0]) % brick_counts_[1]) * brick_,
          static_cast<int>(b / (static_cast<int64_t>(brick_counts_[0]) * brick_counts_[1])) *
              brick_};
      Compute(bricks_[static_cast<size_t>(k)], core_lo, work_[static_cast<size_t>(worker)],
              found[static_cast<size_t>(task)]);
    }
  });
  if (stop.fired()) {
    Release();
    return std::nullopt;
  }
  size_t total = 0;
  for (const std::vector<int64_t>& f : found) total += f.size();
  std::vector<int64_t> joined;
  joined.reserve(total);
  for (const std::vector<int64_t>& f : found) joined.insert(joined.end(), f.begin(), f.end());
  // The bricks' cores are disjoint: every candidate is listed once.
  std::vector<int64_t> candidates(total);
  MakeAndSortUnique(candidates, threads, [&](size_t i) { return joined[i]; });
  return candidates;
}

void LocalSnapshot::Compute(Brick& brick, const Coord& core_lo, BoxPlanes& w,
                            std::vector<int64_t>& candidates) const {
  const int n = n_;
  const std::array<int, 3>& dims = grid_.dims();
  // The core and n + 2 voxels around it: the anchors the core's candidates read (within n - 1
  // below them) read cells up to n + 1 away, off the box's outermost layer.
  Coord core_hi;
  for (int d = 0; d < 3; ++d) {
    core_hi[d] = std::min(core_lo[d] + brick_, dims[d]) - 1;
    brick.lo[d] = std::max(core_lo[d] - (n + 2), 0);
    brick.dims[d] = std::min(core_hi[d] + n + 2, dims[d] - 1) - brick.lo[d] + 1;
  }
  const int64_t nx = brick.dims[0], ny = brick.dims[1], nz = brick.dims[2];
  const int64_t size = nx * ny * nz;
  const int64_t st[3] = {1, nx, nx * ny};
  for (FlatBitset* p : {&w.free, &w.out, &w.bs, &w.free_z, &w.out_z, &w.free_sq, &w.out_sq,
                        &w.covered, &w.anchor, &w.scratch}) {
    p->EnsureSize(size);
  }
  // The box's states, row by row, then its planes as the dense snapshot builds them; the
  // box's outermost layer (which holds the grid's border where the box reaches it) is
  // cleared from `free`: plates touching it are left out, as at the border.
  w.bytes.resize(static_cast<size_t>(size));
  const VoxelState* s = grid_.states().data();
  for (int64_t z = 0; z < nz; ++z)
    for (int64_t y = 0; y < ny; ++y) {
      std::memcpy(w.bytes.data() + nx * (y + ny * z),
                  s + grid_.Index(brick.lo.x, brick.lo.y + static_cast<int>(y),
                                  brick.lo.z + static_cast<int>(z)),
                  static_cast<size_t>(nx));
    }
  const absl::Span<const VoxelState> box_states(w.bytes);
  FillStatePlane(box_states, StatePredicate::kBoundarySoft, w.bs);
  FillStatePlane(box_states, StatePredicate::kOutside, w.out);
  w.free.AssignOr(w.bs, w.out);
  ClearArrayBorder(brick.dims, w.free);
  // The dense snapshot's anchors (place_finder.cc), on the box.
  w.free_z.ErodeRunFrom(w.free, n, st[2]);
  w.out_z.ErodeRunFrom(w.out, n, st[2]);
  FlatBitset& free_x = w.free;
  FlatBitset& out_x = w.out;
  free_x.ErodeRun(n, st[0]);
  out_x.ErodeRun(n, st[0]);
  w.covered.clear_all();
  for (int a = 0; a < 3; ++a) {
    const bool from_z = a != 2;
    const int last_axis = a == 1 ? 0 : 1;
    w.free_sq.ErodeRunFrom(from_z ? w.free_z : free_x, n, st[last_axis]);
    w.out_sq.ErodeRunFrom(from_z ? w.out_z : out_x, n, st[last_axis]);
    const int64_t su = st[(a + 1) % 3], sv = st[(a + 2) % 3];
    for (int o = 2 * a; o < 2 * a + 2; ++o) {
      w.anchor.AssignAndShifted(w.free_sq, w.out_sq, kOrientations[o].sign * st[a]);
      brick.anchors[static_cast<size_t>(o)].Assign(w.anchor);
      w.scratch = w.anchor;
      w.scratch.DilateRun(n, sv);
      w.scratch.DilateRun(n, su);
      w.covered.Or(w.scratch);
    }
  }
  // The core's candidates.
  w.covered.And(w.bs);
  w.covered.ForEach([&](int64_t local) {
    const int64_t x = local % nx, y = (local / nx) % ny, z = local / (nx * ny);
    const Coord c{brick.lo.x + static_cast<int>(x), brick.lo.y + static_cast<int>(y),
                  brick.lo.z + static_cast<int>(z)};
    for (int d = 0; d < 3; ++d) {
      if (c[d] < core_lo[d] || c[d] > core_hi[d]) return;
    }
    candidates.push_back(grid_.Index(c));
  });
}

std::optional<Plate> LocalSnapshot::PlaceFor(int64_t index) const {
  const Coord c = grid_.CoordOf(index);
  const int64_t b = BrickIndex(c.x / brick_, c.y / brick_, c.z / brick_);
  const int32_t k = slot_[static_cast<size_t>(b)];
  if (k < 0) return std::nullopt;
  const Brick& brick = bricks_[static_cast<size_t>(k)];
  const int n = n_;
  for (int o = 0; o < 6; ++o) {
    const Orientation& orient = kOrientations[o];
    const int layer = c[orient.axis], u = c[orient.u_axis()], v = c[orient.v_axis()];
    const PackedPlane& anchors = brick.anchors[static_cast<size_t>(o)];
    for (int u0 = std::max(u - n + 1, 0); u0 <= u; ++u0)
      for (int v0 = std::max(v - n + 1, 0); v0 <= v; ++v0) {
        const Coord p = PlateCell(orient, layer, u0, v0);
        const int64_t local =
            (p.x - brick.lo.x) +
            brick.dims[0] * (static_cast<int64_t>(p.y - brick.lo.y) +
                             static_cast<int64_t>(brick.dims[1]) * (p.z - brick.lo.z));
        if (anchors.test(local)) return Plate{o, layer, u0, v0};
      }
  }
  return std::nullopt;
}

void LocalSnapshot::Release() {
  bricks_.clear();
  slot_.clear();
}

}  // namespace membrane
