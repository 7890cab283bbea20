// The dense snapshot (core/engine/place_finder.h) finds the places of the paper's list scan:
// every boundary soft voxel covered by a fitting plate is a candidate, and its place is the
// first fitting plate in kOrientations order, then u0, then v0. The reference here counts each
// plate's cells with prefix sums, plate by plate, for plate sizes whose runs take the doubling
// passes and sizes whose runs along y and z take the long runs' three passes (17 and more on
// rows of 129 voxels and more).
#include <algorithm>
#include <array>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "absl/strings/str_cat.h"
#include "core/base/cancel_token.h"
#include "core/engine/first_anchored_plate.h"
#include "core/engine/place_finder.h"
#include "core/engine/plate.h"
#include "core/engine/voxel_grid.h"
#include "core/engine/voxel_state.h"
#include "core/engine/work_planes.h"
#include "gtest/gtest.h"
#include "tests/support/random_membrane.h"

namespace membrane {
namespace {

// A grid of `dims` voxels, inside soft but for outside boxes (sides 8 to 60, so that plates of
// 25 fit on their faces) and the two outer layers, with every voxel beside the outside
// boundary (a random few hard or frozen, the rest soft), and a random few voxels anywhere off
// the padding outside or boundary soft.
VoxelGrid BoxesGrid(const std::array<int, 3>& dims, uint32_t seed) {
  VoxelGrid grid(dims, {0, 0, 0}, 1.0);
  std::mt19937 rng(seed);
  auto uniform = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
  auto padding = [&](const Coord& c) {
    return std::min({c.x, c.y, c.z, dims[0] - 1 - c.x, dims[1] - 1 - c.y, dims[2] - 1 - c.z}) <
           VoxelGrid::kPadding;
  };
  std::vector<std::array<Coord, 2>> boxes;
  for (int k = 0; k < 7; ++k) {
    Coord lo, hi;
    for (int d = 0; d < 3; ++d) {
      lo[d] = uniform(2, dims[d] - 10);
      hi[d] = std::min(lo[d] + uniform(8, 60), dims[d] - 3);
    }
    boxes.push_back({lo, hi});
  }
  for (int64_t i = 0; i < grid.size(); ++i) {
    const Coord c = grid.CoordOf(i);
    bool out = padding(c);
    for (const auto& [lo, hi] : boxes) {
      out = out || (c.x >= lo.x && c.x <= hi.x && c.y >= lo.y && c.y <= hi.y && c.z >= lo.z &&
                    c.z <= hi.z);
    }
    if (out) grid.set(i, OutsideState(uniform(0, 3)));
  }
  testing::MarkRandomMembrane(grid, rng, 300);
  return grid;
}

// Inclusive 3-D prefix sums of a predicate over the grid, summed over boxes.
class BoxCounts {
 public:
  template <typename Predicate>
  BoxCounts(const VoxelGrid& grid, const Predicate& predicate) : dims_(grid.dims()) {
    sums_.assign(static_cast<size_t>(dims_[0] + 1) * (dims_[1] + 1) * (dims_[2] + 1), 0);
    for (int z = 0; z < dims_[2]; ++z)
      for (int y = 0; y < dims_[1]; ++y)
        for (int x = 0; x < dims_[0]; ++x) {
          const Coord c{x, y, z};
          At(x + 1, y + 1, z + 1) = (predicate(c) ? 1 : 0) + At(x, y + 1, z + 1) +
                                    At(x + 1, y, z + 1) + At(x + 1, y + 1, z) -
                                    At(x, y, z + 1) - At(x, y + 1, z) - At(x + 1, y, z) +
                                    At(x, y, z);
        }
  }

  // Voxels of [lo, hi] (inclusive, inside the grid) the predicate holds for.
  int64_t Count(const Coord& lo, const Coord& hi) const {
    const int x0 = lo.x, y0 = lo.y, z0 = lo.z, x1 = hi.x + 1, y1 = hi.y + 1, z1 = hi.z + 1;
    return At(x1, y1, z1) - At(x0, y1, z1) - At(x1, y0, z1) - At(x1, y1, z0) + At(x0, y0, z1) +
           At(x0, y1, z0) + At(x1, y0, z0) - At(x0, y0, z0);
  }

 private:
  int64_t& At(int x, int y, int z) {
    return sums_[static_cast<size_t>(x + (dims_[0] + 1) * (y + (dims_[1] + 1) * z))];
  }
  int64_t At(int x, int y, int z) const {
    return sums_[static_cast<size_t>(x + (dims_[0] + 1) * (y + (dims_[1] + 1) * z))];
  }

  std::array<int, 3> dims_;
  std::vector<int64_t> sums_;
};

// The paper's plate test: the plate of orientation o with lowest corner `corner` fits when its
// n x n cells are all outside or boundary soft and off the array border, and its back side
// (the same square at layer - sign) is all outside.
bool PlateFits(const VoxelGrid& grid, const BoxCounts& free_cells, const BoxCounts& outside,
               int o, const Coord& corner, int n) {
  const Orientation& orient = kOrientations[o];
  Coord lo = corner, hi = corner;
  hi[orient.u_axis()] += n - 1;
  hi[orient.v_axis()] += n - 1;
  for (int d = 0; d < 3; ++d) {
    if (lo[d] < 0 || hi[d] >= grid.dims()[d]) return false;
  }
  if (free_cells.Count(lo, hi) != static_cast<int64_t>(n) * n) return false;
  lo[orient.axis] -= orient.sign;
  hi[orient.axis] -= orient.sign;
  if (lo[orient.axis] < 0 || lo[orient.axis] >= grid.dims()[orient.axis]) return false;
  return outside.Count(lo, hi) == static_cast<int64_t>(n) * n;
}

TEST(PlaceFinderTest, DenseSnapshotIsThePaperListScan) {
  const CancelToken cancel;
  for (uint32_t seed : {1u, 2u}) {
    const VoxelGrid grid = BoxesGrid({150, 64, 60}, seed);
    const BoxCounts free_cells(grid, [&](const Coord& c) {
      const VoxelState s = grid.at(c);
      return (IsOutside(s) || s == kBoundarySoft) && !grid.OnArrayBorder(c);
    });
    const BoxCounts outside(grid, [&](const Coord& c) { return IsOutside(grid.at(c)); });
    for (int threads : {1, 2}) {
      WorkPlanes planes(grid, threads);
      PlaceFinder finder(grid, planes);
      for (int n : {1, 2, 7, 8, 13, 17, 25}) {
        const std::string at = absl::StrCat("seed ", seed, ", ", threads, " thread(s), n = ", n);
        const std::optional<std::vector<int64_t>> candidates = finder.Snapshot(n, cancel);
        ASSERT_TRUE(candidates.has_value()) << at;
        std::vector<int64_t> expected;
        std::vector<Plate> places;
        for (int64_t i = 0; i < grid.size(); ++i) {
          if (grid.at(i) != kBoundarySoft) continue;
          const std::optional<Plate> plate = FirstAnchoredPlate(
              grid.CoordOf(i), n,
              [&](int o, const Coord& cell) {
                return PlateFits(grid, free_cells, outside, o, cell, n);
              },
              [](int, const Coord&) { return true; });
          if (!plate) continue;
          expected.push_back(i);
          places.push_back(*plate);
        }
        EXPECT_GT(expected.size(), 100u) << at;  // plates of every size fit somewhere
        ASSERT_EQ(*candidates, expected) << at;
        for (size_t k = 0; k < expected.size(); ++k) {
          const std::optional<Plate> place = finder.PlaceFor(expected[k]);
          ASSERT_TRUE(place.has_value()) << at << ", voxel " << expected[k];
          const Plate& b = places[k];
          EXPECT_TRUE(place->orientation == b.orientation && place->layer == b.layer &&
                      place->u0 == b.u0 && place->v0 == b.v0)
              << at << ", voxel " << expected[k];
        }
      }
    }
  }
}

}  // namespace
}  // namespace membrane
