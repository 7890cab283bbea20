#include "core/engine/local_snapshot.h"

#include <algorithm>
#include <bit>
#include <cstring>

#include "absl/types/span.h"
#include "core/base/parallel_tasks.h"
#include "core/base/split_sort.h"
#include "core/engine/first_anchored_plate.h"
#include "core/engine/interior_plane.h"
#include "core/engine/state_planes.h"
#include "core/engine/voxel_state.h"

namespace membrane {
namespace {

// Fewer bricks than this are computed on the calling thread: starting threads would cost more
// than the bricks (a brick's box is some 40^3 voxels).
constexpr int64_t kMinBricksToSplit = 16;

// The voxels a brick's box holds around its core on each side at plate size n. A core
// candidate's plates have their cells within n - 1 of it along u and v (the corner below,
// the far edge above) and their back cells 1 away along the plate's axis, and the box's
// outermost layer is cleared from the free cells as the grid's border is: a margin of n keeps
// every cell a core candidate's search reads off that layer, and n - 1 does not.
int BoxMargin(int n) { return n; }

}  // namespace

std::optional<std::vector<int64_t>> LocalSnapshot::Plan(int n,
                                                        const std::vector<VoxelBox>& written,
                                                        const LocalSnapshotOptions& options) {
  if (options.max_share <= 0 || options.brick < 1 || options.brick_plates < 0) {
    return std::nullopt;
  }
  // A key holds the voxel index and the place: 6 n^2 places.
  const int index_bits = std::bit_width(static_cast<uint64_t>(grid_.size()) - 1);
  place_bits_ =
      std::bit_width(uint64_t{6} * static_cast<uint64_t>(n) * static_cast<uint64_t>(n) - 1);
  if (index_bits + place_bits_ > 64) return std::nullopt;
  n_ = n;
  brick_ = std::max(options.brick, options.brick_plates * n);
  const std::array<int, 3>& dims = grid_.dims();
  for (int d = 0; d < 3; ++d) brick_counts_[d] = (dims[d] + brick_ - 1) / brick_;
  std::vector<uint8_t> near(
      static_cast<size_t>(brick_counts_[0]) * brick_counts_[1] * brick_counts_[2], 0);
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
          if (near[static_cast<size_t>(b)] == 0) {
            near[static_cast<size_t>(b)] = 1;
            marked.push_back(b);
          }
        }
  }
  std::sort(marked.begin(), marked.end());
  const int64_t side = brick_ + 2 * BoxMargin(n);
  if (static_cast<double>(marked.size()) * static_cast<double>(side * side * side) >
      options.max_share * static_cast<double>(grid_.size())) {
    return std::nullopt;
  }
  return marked;
}

std::optional<std::vector<int64_t>> LocalSnapshot::Take(int n, const std::vector<VoxelBox>& written,
                                                        const LocalSnapshotOptions& options,
                                                        const CancelToken& cancel) {
  keys_ = {};  // the last snapshot's places
  const std::optional<std::vector<int64_t>> planned = Plan(n, written, options);
  if (!planned) return std::nullopt;
  const std::vector<int64_t>& marked = *planned;
  // A range of bricks a task, a few ranges a thread so that ranges of busy bricks even out;
  // each brick reads the grid and writes only its own thread's planes and its range's keys,
  // which are joined in range order and sorted: the same list for any thread count.
  const int threads = static_cast<int>(work_.size());
  const TaskRanges ranges =
      TaskRanges::Split(static_cast<int64_t>(marked.size()), threads, 8, kMinBricksToSplit);
  std::vector<std::vector<uint64_t>> found(static_cast<size_t>(ranges.tasks));
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
      Compute(core_lo, work_[static_cast<size_t>(worker)], found[static_cast<size_t>(task)]);
    }
  });
  if (stop.fired()) {
    Release();
    return std::nullopt;
  }
  // The box planes are freed with every snapshot (at n = 25 some 13 MB a thread): the chains
  // and the next steps take their room instead of growing the heap.
  for (BoxPlanes& w : work_) w = BoxPlanes();
  size_t total = 0;
  for (const std::vector<uint64_t>& f : found) total += f.size();
  keys_.reserve(total);
  for (std::vector<uint64_t>& f : found) {
    keys_.insert(keys_.end(), f.begin(), f.end());
    f = {};
  }
  // The bricks' cores are disjoint: every candidate is listed once, and the keys are unique.
  // Each key is made from itself: the sort needs no second copy of the list to make from.
  MakeAndSortUnique(keys_, threads, [&](size_t i) { return keys_[i]; });
  std::vector<int64_t> candidates(total);
  for (size_t i = 0; i < total; ++i) candidates[i] = static_cast<int64_t>(keys_[i] >> place_bits_);
  return candidates;
}

void LocalSnapshot::Compute(const Coord& core_lo, BoxPlanes& w,
                            std::vector<uint64_t>& keys) const {
  const int n = n_;
  const std::array<int, 3>& dims = grid_.dims();
  // The core and BoxMargin(n) voxels around it.
  const int margin = BoxMargin(n);
  Coord lo, core_hi;
  std::array<int, 3> box_dims;
  for (int d = 0; d < 3; ++d) {
    core_hi[d] = std::min(core_lo[d] + brick_, dims[d]) - 1;
    lo[d] = std::max(core_lo[d] - margin, 0);
    box_dims[d] = std::min(core_hi[d] + margin, dims[d] - 1) - lo[d] + 1;
  }
  const int64_t nx = box_dims[0], ny = box_dims[1], nz = box_dims[2];
  const int64_t size = nx * ny * nz;
  const int64_t st[3] = {1, nx, nx * ny};
  for (FlatBitset* p : {&w.free, &w.out, &w.bs, &w.free_z, &w.out_z, &w.free_sq, &w.out_sq,
                        &w.covered, &w.scratch}) {
    p->EnsureSize(size);
  }
  for (int o = 0; o < 6; ++o) {
    w.anchors[static_cast<size_t>(o)].EnsureSize(size);
    w.rows[static_cast<size_t>(o)].EnsureSize(size);
  }
  // The box's states, row by row, then its planes as the dense snapshot builds them; the
  // box's outermost layer (which holds the grid's border where the box reaches it) is
  // cleared from `free`: plates touching it are left out, as at the border.
  w.bytes.resize(static_cast<size_t>(size));
  const VoxelState* s = grid_.states().data();
  for (int64_t z = 0; z < nz; ++z)
    for (int64_t y = 0; y < ny; ++y) {
      std::memcpy(w.bytes.data() + nx * (y + ny * z),
                  s + grid_.Index(lo.x, lo.y + static_cast<int>(y), lo.z + static_cast<int>(z)),
                  static_cast<size_t>(nx));
    }
  const absl::Span<const VoxelState> box_states(w.bytes);
  FillStatePlane(box_states, StatePredicate::kBoundarySoft, w.bs);
  FillStatePlane(box_states, StatePredicate::kOutside, w.out);
  w.free.AssignOr(w.bs, w.out);
  ClearArrayBorder(box_dims, w.free);
  // The dense snapshot's anchors and rows (place_finder.cc), on the box.
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
      FlatBitset& anchors = w.anchors[static_cast<size_t>(o)];
      anchors.AssignAndShifted(w.free_sq, w.out_sq, kOrientations[o].sign * st[a]);
      w.rows[static_cast<size_t>(o)].DilateRunFrom(anchors, n, sv);
    }
    // The cells the axis' plates cover: both signs' rows dilated along u.
    w.scratch.AssignOr(w.rows[static_cast<size_t>(2 * a)], w.rows[static_cast<size_t>(2 * a + 1)]);
    w.scratch.DilateRun(n, su);
    w.covered.Or(w.scratch);
  }
  // The core's candidates, each with its place, found on the box's planes.
  w.covered.And(w.bs);
  auto local = [&](const Coord& c) {
    return (c.x - lo.x) + nx * (static_cast<int64_t>(c.y - lo.y) + ny * (c.z - lo.z));
  };
  auto anchor = [&](int o, const Coord& cell) {
    return w.anchors[static_cast<size_t>(o)].test(local(cell));
  };
  auto row = [&](int o, const Coord& cell) {
    return w.rows[static_cast<size_t>(o)].test(local(cell));
  };
  w.covered.ForEach([&](int64_t i) {
    const int64_t x = i % nx, y = (i / nx) % ny, z = i / (nx * ny);
    const Coord c{lo.x + static_cast<int>(x), lo.y + static_cast<int>(y),
                  lo.z + static_cast<int>(z)};
    for (int d = 0; d < 3; ++d) {
      if (c[d] < core_lo[d] || c[d] > core_hi[d]) return;
    }
    // A candidate is covered by an anchored plate, so it has a place. One without would be
    // skipped by the pass (PlaceFor nullopt), which is what leaving it out does.
    const std::optional<Plate> plate = FirstAnchoredPlate(c, n, anchor, row);
    if (!plate) return;
    const Orientation& orient = kOrientations[plate->orientation];
    const uint64_t place =
        (static_cast<uint64_t>(plate->orientation) * static_cast<uint64_t>(n) +
         static_cast<uint64_t>(c[orient.u_axis()] - plate->u0)) *
            static_cast<uint64_t>(n) +
        static_cast<uint64_t>(c[orient.v_axis()] - plate->v0);
    keys.push_back(static_cast<uint64_t>(grid_.Index(c)) << place_bits_ | place);
  });
}

std::optional<Plate> LocalSnapshot::PlaceFor(int64_t index) const {
  const uint64_t key = static_cast<uint64_t>(index) << place_bits_;
  const auto it = std::lower_bound(keys_.begin(), keys_.end(), key);
  if (it == keys_.end() || (*it >> place_bits_) != static_cast<uint64_t>(index)) {
    return std::nullopt;
  }
  const uint64_t n = static_cast<uint64_t>(n_);
  const uint64_t place = *it & ((uint64_t{1} << place_bits_) - 1);
  const int dv = static_cast<int>(place % n), du = static_cast<int>(place / n % n);
  const int o = static_cast<int>(place / (n * n));
  const Orientation& orient = kOrientations[o];
  const Coord c = grid_.CoordOf(index);
  return Plate{o, c[orient.axis], c[orient.u_axis()] - du, c[orient.v_axis()] - dv};
}

void LocalSnapshot::Release() {
  keys_ = {};
  for (BoxPlanes& w : work_) w = BoxPlanes();
}

}  // namespace membrane
