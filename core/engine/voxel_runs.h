// Run-length form of a voxel grid for connectivity: maximal runs of voxels along x in each row
// (y, z), joined into components with a union-find over runs of neighbouring rows. Work and
// memory grow with the number of runs (a few per row on a reconstruction grid), not with the
// number of voxels, which is what makes the shell, genus and cavity counts cheap on 10^8-voxel
// grids.
#ifndef MEMBRANE_CORE_ENGINE_VOXEL_RUNS_H_
#define MEMBRANE_CORE_ENGINE_VOXEL_RUNS_H_

#include <array>
#include <cstdint>
#include <vector>

#include "core/engine/voxel_grid.h"

namespace membrane {

// Voxels [begin, end) along x of one row.
struct VoxelRun {
  int32_t begin = 0;
  int32_t end = 0;
  int32_t component = -1;  // set by LabelRunComponents()
};

// Runs of one kind of voxel, row by row in flat index order: row r = y + ny * z holds
// runs[row_begin[r] .. row_begin[r + 1]), sorted by x and never touching each other.
struct VoxelRuns {
  std::array<int, 3> dims{0, 0, 0};  // of the grid the runs come from, in voxels
  std::vector<int64_t> row_begin;     // ny * nz + 1 entries
  std::vector<VoxelRun> runs;

  int64_t rows() const { return static_cast<int64_t>(row_begin.size()) - 1; }
  int64_t Row(int y, int z) const { return y + static_cast<int64_t>(dims[1]) * z; }
};

// The maximal runs of non-outside voxels of `grid`, unlabeled. Any grid, border included.
VoxelRuns NonOutsideRuns(const VoxelGrid& grid);

// The same runs, read on `threads` (slabs of z planes, joined in order): the same result for
// any thread count.
VoxelRuns NonOutsideRuns(const VoxelGrid& grid, int threads);

// The maximal runs of outside voxels of the grid `solid` was taken from that lie off the array
// border (x, y, z in [1, n - 2]): the complement of `solid` in that box, unlabeled.
VoxelRuns OutsideRunsOffBorder(const VoxelRuns& solid);

// How runs of neighbouring rows connect.
enum class RunAdjacency {
  kFace,    // 6-connectivity: rows y +- 1 or z +- 1, x ranges overlapping
  kVertex,  // 26-connectivity: the 8 rows around, x ranges overlapping or touching at an end
};

// Sets each run's `component` to the index of its connected component (voxels of the runs,
// connected under `adjacency`), components numbered in order of their lowest voxel index.
// Returns the number of components.
int LabelRunComponents(VoxelRuns& runs, RunAdjacency adjacency);

}  // namespace membrane

#endif  // MEMBRANE_CORE_ENGINE_VOXEL_RUNS_H_
