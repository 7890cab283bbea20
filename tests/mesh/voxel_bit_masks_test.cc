#include "core/mesh/voxel_bit_masks.h"

#include <array>
#include <cstdint>
#include <random>
#include <vector>

#include "gtest/gtest.h"

namespace membrane {
namespace {

// The 3x3x3 box filter one voxel at a time, voxels beyond the array reading as `erode`.
std::vector<char> ReferenceBox(const std::array<int, 3>& n, const std::vector<char>& m,
                               bool erode) {
  std::vector<char> out(m.size());
  for (int z = 0; z < n[2]; ++z)
    for (int y = 0; y < n[1]; ++y)
      for (int x = 0; x < n[0]; ++x) {
        char v = erode ? 1 : 0;
        for (int dz = -1; dz <= 1; ++dz)
          for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
              const int c[3] = {x + dx, y + dy, z + dz};
              bool inside = true;
              for (int a = 0; a < 3; ++a) inside = inside && c[a] >= 0 && c[a] < n[a];
              const char b = inside ? m[c[0] + int64_t{n[0]} * (c[1] + int64_t{n[1]} * c[2])]
                                    : (erode ? 1 : 0);
              v = erode ? (v & b) : (v | b);
            }
        out[x + int64_t{n[0]} * (y + int64_t{n[1]} * z)] = v;
      }
  return out;
}

bool OnBorder(const std::array<int, 3>& n, int64_t i) {
  const int c[3] = {static_cast<int>(i % n[0]), static_cast<int>(i / n[0] % n[1]),
                    static_cast<int>(i / (int64_t{n[0]} * n[1]))};
  for (int a = 0; a < 3; ++a)
    if (c[a] == 0 || c[a] == n[a] - 1) return true;
  return false;
}

// Random masks of random shapes (rows of 1 to 130 voxels, so that rows start anywhere in a
// word and planes span from part of a word to many), each filtered on 1, 2 and 3 threads.
TEST(VoxelBitMasks, BoxFiltersEqualAFilterVoxelByVoxel) {
  std::mt19937 rng(64);
  int64_t compared = 0;
  for (int trial = 0; trial < 240; ++trial) {
    std::uniform_int_distribution<int> side(1, trial < 200 ? 20 : 130);
    std::array<int, 3> n = {side(rng), side(rng), side(rng)};
    if (trial >= 200) n[2] = std::min(n[2], 12);
    const int64_t count = int64_t{n[0]} * n[1] * n[2];
    const double density = std::uniform_real_distribution<double>(0.05, 0.97)(rng);
    std::bernoulli_distribution set(density);
    const bool erode = trial % 2 == 0;
    // Erosions get every border voxel set in half the trials: exact on the border then too.
    const bool border_set = erode && trial % 4 == 0;
    std::vector<char> m(count);
    for (int64_t i = 0; i < count; ++i) m[i] = (set(rng) || (border_set && OnBorder(n, i))) ? 1 : 0;
    const std::vector<char> want = ReferenceBox(n, m, erode);
    for (int threads = 1; threads <= 3; ++threads) {
      FlatBitset bits(count), scratch(count);
      for (int64_t i = 0; i < count; ++i)
        if (m[i]) bits.set(i);
      BoxFilterBits(n, erode, bits, scratch, threads);
      ASSERT_EQ(bits.bits(), count);
      for (int64_t i = 0; i < count; ++i) {
        if (OnBorder(n, i) && !border_set) continue;  // row ends read their neighbour rows
        ASSERT_EQ(bits.test(i), want[i] != 0)
            << "trial " << trial << " dims " << n[0] << "x" << n[1] << "x" << n[2] << " voxel "
            << i << " threads " << threads;
        ++compared;
      }
      if (count % 64 != 0) {
        ASSERT_EQ(bits.words()[bits.word_count() - 1] >> (count % 64), 0u) << "trial " << trial;
      }
    }
  }
  EXPECT_GT(compared, 1000000);
}

TEST(VoxelBitMasks, OutsideBitsAreTheOutsideVoxels) {
  std::mt19937 rng(8);
  for (const std::array<int, 3> n : {std::array<int, 3>{1, 1, 1}, {7, 3, 2}, {64, 2, 1},
                                     {65, 5, 3}, {130, 17, 9}}) {
    VoxelGrid g(n, {0, 0, 0}, 1.0, OutsideState(0));
    std::bernoulli_distribution solid(0.4);
    for (int64_t i = 0; i < g.size(); ++i)
      if (solid(rng)) g.set(i, (i % 3 == 0) ? kBoundaryHard : kInsideSoft);
    for (int threads = 1; threads <= 3; ++threads) {
      const FlatBitset bits = OutsideBits(g, threads);
      ASSERT_EQ(bits.bits(), g.size());
      for (int64_t i = 0; i < g.size(); ++i) ASSERT_EQ(bits.test(i), IsOutside(g.at(i))) << i;
      if (g.size() % 64 != 0) {
        EXPECT_EQ(bits.words()[bits.word_count() - 1] >> (g.size() % 64), 0u);
      }
      for (int64_t first = 0; first + 8 <= g.size(); first += 5) {
        uint64_t want = 0;
        for (int k = 0; k < 8; ++k) want |= uint64_t{IsOutside(g.at(first + k))} << k;
        ASSERT_EQ(EightBits(bits, first), want) << first;
      }
    }
  }
}

}  // namespace
}  // namespace membrane
