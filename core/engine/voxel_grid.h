// A regular voxel grid holding one VoxelState per voxel (paper section 4.1).
//
// The grid includes `kPadding` layers of outside voxels on every side (algorithm-notes 1), so
// every plate's back, lateral and front sides lie inside the array. Voxel (x, y, z) covers the
// model-space box origin + [x, x+1) * voxel_size (and likewise for y, z).
#ifndef MEMBRANE_CORE_ENGINE_VOXEL_GRID_H_
#define MEMBRANE_CORE_ENGINE_VOXEL_GRID_H_

#include <algorithm>
#include <array>
#include <cassert>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <new>
#include <utility>
#include <vector>

#include "core/engine/unset_construct.h"
#include "core/engine/voxel_state.h"

namespace membrane {

// Integer voxel coordinates.
struct Coord {
  int x = 0, y = 0, z = 0;
  int& operator[](int axis) { return axis == 0 ? x : axis == 1 ? y : z; }
  int operator[](int axis) const { return axis == 0 ? x : axis == 1 ? y : z; }
  friend bool operator==(const Coord&, const Coord&) = default;
};

// The row through `c` along axis d of an array of `dims`, numbered over the two other axes:
// y + ny z along x, x + nx z along y, x + nx y along z. Tables of a value per row and axis
// (the runs of a row, its extreme hard voxels) index by it.
inline size_t AxisRowOf(const std::array<int, 3>& dims, int d, const Coord& c) {
  if (d == 0) return c.y + static_cast<size_t>(dims[1]) * c.z;
  if (d == 1) return c.x + static_cast<size_t>(dims[0]) * c.z;
  return c.x + static_cast<size_t>(dims[0]) * c.y;
}

// The 3x3x3 block around a voxel as 27 steps (dx, dy, dz) in {-1, 0, 1}^3, x fastest: step k
// is (k % 3 - 1, k / 3 % 3 - 1, k / 9 - 1), and bit k of the block masks of local_topology.h.
// Step kBlockCentre is the voxel itself, the other 26 are its neighbours.
inline constexpr int kBlockCentre = 13;
inline constexpr std::array<Coord, 27> kBlockSteps = [] {
  std::array<Coord, 27> steps{};
  for (int k = 0; k < 27; ++k) steps[k] = Coord{k % 3 - 1, k / 3 % 3 - 1, k / 9 - 1};
  return steps;
}();
// True for the 6 steps across a face of the voxel.
constexpr bool IsFaceStep(int k) {
  const Coord& d = kBlockSteps[k];
  return (d.x != 0) + (d.y != 0) + (d.z != 0) == 1;
}

// std::allocator with the states left unset by the vector's constructor (unset_construct.h),
// so that the voxelization writes them first on several threads.
template <typename T>
using UnsetAllocator = UnsetConstruct<std::allocator<T>>;

// The states of a grid's voxels, in index order.
using VoxelStates = std::vector<VoxelState, UnsetAllocator<VoxelState>>;

class VoxelGrid {
 public:
  static constexpr int kPadding = 2;
  // Tag of the constructor that leaves the states unset.
  struct Unset {};

  VoxelGrid() = default;
  // A grid of dims[0] x dims[1] x dims[2] voxels (padding included), all set to `fill`.
  // The caller has checked that the grid fits (Voxelize(), the pipeline's memory estimates).
  VoxelGrid(std::array<int, 3> dims, std::array<double, 3> origin, double voxel_size,
            VoxelState fill = kInsideSoft)
      : dims_(dims), origin_(origin), voxel_size_(voxel_size),
        states_(static_cast<size_t>(dims[0]) * dims[1] * dims[2], fill) {
    SetOffsets();
  }
  // The same grid with its states unset: the caller writes every voxel before any is read
  // (Voxelize() does on the run's threads: at 2.2e9 voxels a fill on one thread takes seconds
  // of page faults and writes).
  VoxelGrid(std::array<int, 3> dims, std::array<double, 3> origin, double voxel_size, Unset)
      : dims_(dims), origin_(origin), voxel_size_(voxel_size),
        states_(static_cast<size_t>(dims[0]) * dims[1] * dims[2]) {
    SetOffsets();
  }

  // Size in voxels along x, y, z, padding included.
  const std::array<int, 3>& dims() const { return dims_; }
  int dim(int axis) const { return dims_[axis]; }
  int64_t size() const { return static_cast<int64_t>(states_.size()); }
  // Model-space position of the corner of voxel (0, 0, 0).
  const std::array<double, 3>& origin() const { return origin_; }
  // Edge length l of a voxel, in model units.
  double voxel_size() const { return voxel_size_; }

  // Flat index stride per axis: index = x + nx * (y + ny * z).
  std::array<int64_t, 3> strides() const {
    return {1, dims_[0], static_cast<int64_t>(dims_[0]) * dims_[1]};
  }
  int64_t Index(int x, int y, int z) const {
    return x + static_cast<int64_t>(dims_[0]) * (y + static_cast<int64_t>(dims_[1]) * z);
  }
  int64_t Index(const Coord& c) const { return Index(c.x, c.y, c.z); }
  // Index offsets of the 3x3x3 block (kBlockSteps, in their order, the centre's 0 included)
  // and of the 26 neighbours alone (the same order, the centre left out): index + offset is the
  // voxel one step away, for any voxel not on the array border.
  const std::array<int64_t, 27>& block_offsets() const { return block_offsets_; }
  const std::array<int64_t, 26>& neighbour_offsets() const { return neighbour_offsets_; }
  Coord CoordOf(int64_t index) const {
    Coord c;
    c.x = static_cast<int>(index % dims_[0]);
    index /= dims_[0];
    c.y = static_cast<int>(index % dims_[1]);
    c.z = static_cast<int>(index / dims_[1]);
    return c;
  }
  bool Contains(const Coord& c) const {
    return c.x >= 0 && c.y >= 0 && c.z >= 0 && c.x < dims_[0] && c.y < dims_[1] && c.z < dims_[2];
  }
  // True for voxels on the outermost layer of the array (no full 26-neighbourhood).
  bool OnArrayBorder(const Coord& c) const {
    return c.x == 0 || c.y == 0 || c.z == 0 || c.x == dims_[0] - 1 || c.y == dims_[1] - 1 ||
           c.z == dims_[2] - 1;
  }

  // The state of a voxel in the array (checked in debug builds only: these are the engine's
  // innermost reads and writes).
  VoxelState at(int64_t index) const {
    assert(index >= 0 && index < size());
    return states_[static_cast<size_t>(index)];
  }
  VoxelState at(const Coord& c) const {
    assert(Contains(c));
    return at(Index(c));
  }
  void set(int64_t index, VoxelState s) {
    assert(index >= 0 && index < size());
    states_[static_cast<size_t>(index)] = s;
  }
  void set(const Coord& c, VoxelState s) {
    assert(Contains(c));
    set(Index(c), s);
  }

  // Model-space centre of a voxel.
  std::array<double, 3> Center(const Coord& c) const {
    return {origin_[0] + (c.x + 0.5) * voxel_size_, origin_[1] + (c.y + 0.5) * voxel_size_,
            origin_[2] + (c.z + 0.5) * voxel_size_};
  }

  const VoxelStates& states() const { return states_; }
  VoxelStates& mutable_states() { return states_; }

 private:
  void SetOffsets() {
    const std::array<int64_t, 3> st = strides();
    for (int k = 0, n = 0; k < 27; ++k) {
      const Coord& d = kBlockSteps[k];
      block_offsets_[k] = d.x * st[0] + d.y * st[1] + d.z * st[2];
      if (k != kBlockCentre) neighbour_offsets_[n++] = block_offsets_[k];
    }
  }

  std::array<int, 3> dims_{0, 0, 0};
  std::array<double, 3> origin_{0, 0, 0};
  double voxel_size_ = 1.0;
  VoxelStates states_;
  std::array<int64_t, 27> block_offsets_{};
  std::array<int64_t, 26> neighbour_offsets_{};
};

// True when at least `need` of the voxels within Chebyshev distance r of c are hard (the cube
// clipped to the array; voxels past it count as none). Stops reading at the hard voxel that
// makes `need`: the gap test asks for one, the guard for a rim of data.
inline bool HardVoxelsWithin(const VoxelGrid& grid, const Coord& c, int r, int64_t need) {
  int64_t count = 0;
  for (int z = std::max(c.z - r, 0); z <= std::min(c.z + r, grid.dim(2) - 1); ++z)
    for (int y = std::max(c.y - r, 0); y <= std::min(c.y + r, grid.dim(1) - 1); ++y) {
      const int64_t row = grid.Index(0, y, z);
      for (int x = std::max(c.x - r, 0); x <= std::min(c.x + r, grid.dim(0) - 1); ++x)
        if (IsHard(grid.at(row + x)) && ++count >= need) return true;
    }
  return false;
}

}  // namespace membrane

#endif  // MEMBRANE_CORE_ENGINE_VOXEL_GRID_H_
