#include "core/engine/voxel_runs.h"

#include <algorithm>
#include <cstring>
#include <numeric>

#include "core/base/parallel_tasks.h"

namespace membrane {
namespace {

constexpr uint64_t kHighBits = 0x8080808080808080ull;

// Index of the first voxel at or after x in row `s` (nx voxels) whose outside bit equals
// `outside`, or nx. Eight voxels at a time: rows are mostly long runs.
int FindNext(const VoxelState* s, int x, int nx, bool outside) {
  const uint64_t skip = outside ? 0 : kHighBits;  // the high bits of 8 voxels not wanted
  while (x + 8 <= nx) {
    uint64_t w;
    std::memcpy(&w, s + x, sizeof(w));
    if ((w & kHighBits) != skip) break;
    x += 8;
  }
  while (x < nx && IsOutside(s[x]) != outside) ++x;
  return x;
}

// Union-find over run indices whose root is always the lowest index of its set, so roots in
// index order are components in order of their lowest voxel.
class RunSets {
 public:
  explicit RunSets(size_t n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), 0); }

  int32_t Find(int32_t i) {
    while (parent_[static_cast<size_t>(i)] != i) {
      const int32_t up = parent_[static_cast<size_t>(parent_[static_cast<size_t>(i)])];
      parent_[static_cast<size_t>(i)] = up;  // path halving
      i = up;
    }
    return i;
  }
  void Join(int32_t a, int32_t b) {
    a = Find(a);
    b = Find(b);
    if (a < b) parent_[static_cast<size_t>(b)] = a;
    else if (b < a) parent_[static_cast<size_t>(a)] = b;
  }

 private:
  std::vector<int32_t> parent_;
};

// Joins the overlapping runs of two rows, [a, a_end) and [b, b_end); runs [p, q) and [u, v)
// connect when p < v + widen and u < q + widen.
void JoinRows(const std::vector<VoxelRun>& runs, int64_t a, int64_t a_end, int64_t b, int64_t b_end,
              int widen, RunSets& sets) {
  while (a < a_end && b < b_end) {
    const VoxelRun& ra = runs[static_cast<size_t>(a)];
    const VoxelRun& rb = runs[static_cast<size_t>(b)];
    if (ra.begin < rb.end + widen && rb.begin < ra.end + widen) {
      sets.Join(static_cast<int32_t>(a), static_cast<int32_t>(b));
    }
    // The run ending first can meet nothing further along the other row.
    if (ra.end < rb.end) ++a;
    else ++b;
  }
}

}  // namespace

VoxelRuns NonOutsideRuns(const VoxelGrid& grid) { return NonOutsideRuns(grid, 1); }

VoxelRuns NonOutsideRuns(const VoxelGrid& grid, int threads) {
  VoxelRuns out;
  out.dims = grid.dims();
  const int nx = out.dims[0], ny = out.dims[1], nz = out.dims[2];
  const VoxelState* s = grid.states().data();
  // Appends the runs of planes [z0, z1) to `runs` and each row's first run to `row_begin`.
  auto read_planes = [&](int z0, int z1, std::vector<int64_t>& row_begin,
                         std::vector<VoxelRun>& runs) {
    for (int z = z0; z < z1; ++z)
      for (int y = 0; y < ny; ++y) {
        row_begin.push_back(static_cast<int64_t>(runs.size()));
        const VoxelState* row = s + grid.Index(0, y, z);
        int x = FindNext(row, 0, nx, false);
        while (x < nx) {
          const int end = FindNext(row, x, nx, true);
          runs.push_back({x, end, -1});
          x = FindNext(row, end, nx, false);
        }
      }
  };
  // A pass over the whole grid (2e9 voxels at 10M points) is worth splitting; a small grid's
  // is not.
  const TaskRanges slabs =
      TaskRanges::Split(nz, grid.size() < kMinSplitGridVoxels ? 1 : threads, /*per_thread=*/4);
  if (slabs.tasks == 1) {
    out.row_begin.reserve(static_cast<size_t>(ny) * static_cast<size_t>(nz) + 1);
    read_planes(0, nz, out.row_begin, out.runs);
    out.row_begin.push_back(static_cast<int64_t>(out.runs.size()));
    return out;
  }
  // Each slab's rows and runs on its own, then joined in slab order: each slab's row starts
  // offset by the runs of the slabs before it, so the list is the one-slab list.
  std::vector<std::vector<int64_t>> slab_rows(static_cast<size_t>(slabs.tasks));
  std::vector<std::vector<VoxelRun>> slab_runs(static_cast<size_t>(slabs.tasks));
  RunTasks(threads, slabs.tasks, [&](int, int64_t t) {
    read_planes(static_cast<int>(slabs.begin(t)), static_cast<int>(slabs.end(t)),
                slab_rows[static_cast<size_t>(t)], slab_runs[static_cast<size_t>(t)]);
  });
  std::vector<int64_t> first_run(static_cast<size_t>(slabs.tasks) + 1, 0);
  for (size_t t = 0; t < slab_runs.size(); ++t) {
    first_run[t + 1] = first_run[t] + static_cast<int64_t>(slab_runs[t].size());
  }
  out.row_begin.resize(static_cast<size_t>(ny) * static_cast<size_t>(nz) + 1);
  out.runs.resize(static_cast<size_t>(first_run.back()));
  RunTasks(threads, slabs.tasks, [&](int, int64_t t) {
    const size_t k = static_cast<size_t>(t);
    const size_t row0 = static_cast<size_t>(slabs.begin(t)) * static_cast<size_t>(ny);
    for (size_t r = 0; r < slab_rows[k].size(); ++r) {
      out.row_begin[row0 + r] = slab_rows[k][r] + first_run[k];
    }
    std::copy(slab_runs[k].begin(), slab_runs[k].end(), out.runs.begin() + first_run[k]);
    std::vector<int64_t>().swap(slab_rows[k]);
    std::vector<VoxelRun>().swap(slab_runs[k]);
  });
  out.row_begin.back() = first_run.back();
  return out;
}

VoxelRuns OutsideRunsOffBorder(const VoxelRuns& solid) {
  VoxelRuns out;
  out.dims = solid.dims;
  const int nx = out.dims[0], ny = out.dims[1], nz = out.dims[2];
  out.row_begin.reserve(static_cast<size_t>(solid.row_begin.size()));
  for (int z = 0; z < nz; ++z)
    for (int y = 0; y < ny; ++y) {
      out.row_begin.push_back(static_cast<int64_t>(out.runs.size()));
      if (y < 1 || z < 1 || y > ny - 2 || z > nz - 2) continue;
      const int64_t r = solid.Row(y, z);
      int x = 1;  // first voxel of the current gap between solid runs
      for (int64_t i = solid.row_begin[static_cast<size_t>(r)]; i < solid.row_begin[static_cast<size_t>(r) + 1];
           ++i) {
        const VoxelRun& run = solid.runs[static_cast<size_t>(i)];
        const int end = std::min(run.begin, nx - 1);
        if (x < end) out.runs.push_back({x, end, -1});
        x = std::max(x, run.end);
      }
      if (x < nx - 1) out.runs.push_back({x, nx - 1, -1});
    }
  out.row_begin.push_back(static_cast<int64_t>(out.runs.size()));
  return out;
}

int LabelRunComponents(VoxelRuns& runs, RunAdjacency adjacency) {
  const int ny = runs.dims[1], nz = runs.dims[2];
  const bool vertex = adjacency == RunAdjacency::kVertex;
  const int widen = vertex ? 1 : 0;
  RunSets sets(runs.runs.size());
  // Each pair of neighbouring rows is joined once, from the later row to the earlier one.
  for (int z = 0; z < nz; ++z)
    for (int y = 0; y < ny; ++y) {
      const int64_t r = runs.Row(y, z);
      const int64_t a = runs.row_begin[static_cast<size_t>(r)], a_end = runs.row_begin[static_cast<size_t>(r) + 1];
      if (a == a_end) continue;
      auto join = [&](int qy, int qz) {
        if (qy < 0 || qy >= ny || qz < 0) return;
        const int64_t q = runs.Row(qy, qz);
        JoinRows(runs.runs, a, a_end, runs.row_begin[static_cast<size_t>(q)],
                 runs.row_begin[static_cast<size_t>(q) + 1], widen, sets);
      };
      join(y - 1, z);
      join(y, z - 1);
      if (vertex) {
        join(y - 1, z - 1);
        join(y + 1, z - 1);
      }
    }
  int components = 0;
  for (size_t i = 0; i < runs.runs.size(); ++i) {
    const int32_t root = sets.Find(static_cast<int32_t>(i));
    runs.runs[i].component =
        root == static_cast<int32_t>(i) ? components++ : runs.runs[static_cast<size_t>(root)].component;
  }
  return components;
}

}  // namespace membrane
