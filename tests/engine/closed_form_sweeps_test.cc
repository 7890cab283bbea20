// The closed form's sweeps (closed_form_sweeps.h) against the plate rule applied plate by
// plate on random boxes: the same least fixed point, from the outside voxels or from any start
// between them and it.
#include "core/engine/closed_form_sweeps.h"

#include <algorithm>
#include <array>
#include <random>

#include "core/engine/interior_plane.h"
#include "gtest/gtest.h"

namespace membrane {
namespace {

int64_t IndexIn(const PlaneBox& box, int x, int y, int z) {
  return x + box.strides[1] * y + box.strides[2] * z;
}

int64_t IndexIn(const PlaneBox& box, const std::array<int, 3>& c) {
  return IndexIn(box, c[0], c[1], c[2]);
}

// The plate rule's least fixed point, plate by plate: a plate of n x n free cells whose back
// square is all outside becomes outside, in every orientation, until nothing changes.
FlatBitset PlateByPlateFixedPoint(const FlatBitset& free_cells, FlatBitset out, int n,
                                  const PlaneBox& box) {
  for (bool changed = true; changed;) {
    changed = false;
    for (int a = 0; a < 3; ++a) {
      const int u = (a + 1) % 3, v = (a + 2) % 3;
      for (int sign : {1, -1}) {
        std::array<int, 3> c;
        for (c[a] = 1; c[a] + 1 < box.dims[a]; ++c[a])
          for (c[u] = 0; c[u] + n <= box.dims[u]; ++c[u])
            for (c[v] = 0; c[v] + n <= box.dims[v]; ++c[v]) {
              bool fits = true, all_out = true;
              for (int i = 0; i < n && fits; ++i)
                for (int j = 0; j < n && fits; ++j) {
                  std::array<int, 3> p = c;
                  p[u] += i;
                  p[v] += j;
                  fits = free_cells.test(IndexIn(box, p));
                  all_out = all_out && out.test(IndexIn(box, p));
                  p[a] -= sign;
                  fits = fits && out.test(IndexIn(box, p));
                }
              if (!fits || all_out) continue;
              for (int i = 0; i < n; ++i)
                for (int j = 0; j < n; ++j) {
                  std::array<int, 3> p = c;
                  p[u] += i;
                  p[v] += j;
                  out.set(IndexIn(box, p));
                }
              changed = true;
            }
      }
    }
  }
  return out;
}

// A padded grid's planes: outside on the two outer layers; balls of hard voxels (not free)
// inside, and the outermost layer not free, as on a grid.
struct RandomBox {
  PlaneBox box;
  FlatBitset free_cells, out0;
};

RandomBox MakeRandomBox(const std::array<int, 3>& dims, int balls, uint32_t seed) {
  RandomBox g;
  g.box = MakePlaneBox(dims);
  g.free_cells = InteriorPlane(dims);
  g.out0 = FlatBitset(g.box.size());
  std::mt19937 rng(seed);
  std::vector<std::array<int, 4>> centres(static_cast<size_t>(balls));
  for (auto& b : centres) {
    for (int d = 0; d < 3; ++d) b[d] = std::uniform_int_distribution<int>(4, dims[d] - 5)(rng);
    b[3] = std::uniform_int_distribution<int>(1, 4)(rng);
  }
  FlatBitset hard(g.box.size());
  for (int z = 0; z < dims[2]; ++z)
    for (int y = 0; y < dims[1]; ++y)
      for (int x = 0; x < dims[0]; ++x) {
        const int64_t i = IndexIn(g.box, x, y, z);
        if (std::min({x, y, z, dims[0] - 1 - x, dims[1] - 1 - y, dims[2] - 1 - z}) < 2)
          g.out0.set(i);
        for (const auto& b : centres) {
          const int dx = x - b[0], dy = y - b[1], dz = z - b[2];
          if (dx * dx + dy * dy + dz * dz <= b[3] * b[3]) hard.set(i);
        }
      }
  g.free_cells.AndNot(hard);
  return g;
}

// SweepToFixedPoint from `start`, with the square planes of g's free cells, every plane's word
// passes on `threads` threads.
FlatBitset Sweep(const RandomBox& g, FlatBitset start, int n, int threads = 1) {
  const int64_t nv = g.box.size();
  FlatBitset squares[3] = {FlatBitset(nv), FlatBitset(nv), FlatBitset(nv)};
  FlatBitset* sq[3] = {&squares[0], &squares[1], &squares[2]};
  FlatBitset back(nv), reach(nv), reach_back(nv), scratch(nv);
  for (FlatBitset* p : {sq[0], sq[1], sq[2], &back, &reach, &reach_back, &scratch, &start}) {
    p->set_threads(threads);
  }
  FreeSquares(g.free_cells, n, g.box, sq, scratch);
  const SweepPlanes planes{{sq[0], sq[1], sq[2]}, &back, &reach, &reach_back, &scratch};
  const std::optional<int> rounds = SweepToFixedPoint(start, n, g.box, planes, CancelToken::Never());
  EXPECT_TRUE(rounds.has_value());
  return start;
}

TEST(ClosedFormSweeps, ReachThePlateRulesLeastFixedPointFromAnyStartBelowIt) {
  int grown = 0;
  for (uint32_t seed = 1; seed <= 6; ++seed) {
    const std::array<int, 3> dims = {19 + static_cast<int>(seed % 3), 18 + static_cast<int>(seed % 2),
                                     21 + static_cast<int>(seed % 4)};
    const RandomBox g = MakeRandomBox(dims, static_cast<int>(2 + seed), seed);
    for (int n : {1, 2, 3, 5, 8}) {
      const FlatBitset truth = PlateByPlateFixedPoint(g.free_cells, g.out0, n, g.box);
      // A start between the outside voxels and the fixed point: a random part of the latter.
      FlatBitset between = g.out0;
      std::mt19937 rng(seed * 100 + static_cast<uint32_t>(n));
      truth.ForEach([&](int64_t i) {
        if (rng() % 3 == 0) between.set(i);
      });
      for (const FlatBitset& start : {g.out0, between}) {
        const FlatBitset swept = Sweep(g, start, n);
        for (int64_t i = 0; i < g.box.size(); ++i)
          ASSERT_EQ(swept.test(i), truth.test(i)) << "seed " << seed << " n " << n << " voxel " << i;
      }
      grown += truth.Count() > g.out0.Count();
      // The balls keep some voxels inside.
      EXPECT_LT(truth.Count(), g.box.size()) << "seed " << seed << " n " << n;
    }
  }
  EXPECT_EQ(grown, 30);  // every case had plates to apply
}

// Plates of 17 and more across rows of 129 voxels and more: the erosions and dilations along y
// and z are the long runs' cell passes (flat_bitset_long_runs.cc), side by side on threads.
TEST(ClosedFormSweeps, LongRunsReachTheLeastFixedPointOnAnyThreadCount) {
  int grown = 0;
  for (uint32_t seed = 1; seed <= 2; ++seed) {
    const std::array<int, 3> dims = {131 + static_cast<int>(seed), 24, 23 + static_cast<int>(seed)};
    const RandomBox g = MakeRandomBox(dims, 2, seed);
    for (int n : {17, 19}) {
      const FlatBitset truth = PlateByPlateFixedPoint(g.free_cells, g.out0, n, g.box);
      for (int threads : {1, 3}) {
        const FlatBitset swept = Sweep(g, g.out0, n, threads);
        for (int64_t i = 0; i < g.box.size(); ++i)
          ASSERT_EQ(swept.test(i), truth.test(i))
              << "seed " << seed << " n " << n << " threads " << threads << " voxel " << i;
      }
      grown += truth.Count() > g.out0.Count();
    }
  }
  EXPECT_EQ(grown, 4);  // every case had plates to apply
}

}  // namespace
}  // namespace membrane
