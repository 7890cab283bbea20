#include "core/mesh/border_flood.h"

#include <array>
#include <cstdint>
#include <random>
#include <vector>

#include "gtest/gtest.h"

namespace membrane {
namespace {

// Plain breadth-first flood, one voxel at a time, from every open border voxel.
std::vector<char> ReferenceFlood(const std::array<int, 3>& n, const std::vector<char>& open) {
  const int64_t sy = n[0], sz = int64_t{n[0]} * n[1];
  std::vector<char> reached(open.size(), 0);
  std::vector<int64_t> queue;
  for (int z = 0; z < n[2]; ++z)
    for (int y = 0; y < n[1]; ++y)
      for (int x = 0; x < n[0]; ++x) {
        const bool border = x == 0 || y == 0 || z == 0 || x == n[0] - 1 || y == n[1] - 1 ||
                            z == n[2] - 1;
        const int64_t i = x + y * sy + z * sz;
        if (border && open[i]) {
          reached[i] = 1;
          queue.push_back(i);
        }
      }
  for (size_t head = 0; head < queue.size(); ++head) {
    const int64_t i = queue[head];
    const int c[3] = {static_cast<int>(i % sy), static_cast<int>(i / sy % n[1]),
                      static_cast<int>(i / sz)};
    const int64_t step[3] = {1, sy, sz};
    for (int a = 0; a < 3; ++a)
      for (int dir : {-1, 1}) {
        const int to = c[a] + dir;
        if (to < 0 || to >= n[a]) continue;
        const int64_t j = i + dir * step[a];
        if (open[j] && !reached[j]) {
          reached[j] = 1;
          queue.push_back(j);
        }
      }
  }
  return reached;
}

// The open voxels of `open` (one byte a voxel) as bits.
FlatBitset OpenBits(const std::vector<char>& open) {
  FlatBitset bits(static_cast<int64_t>(open.size()));
  for (size_t i = 0; i < open.size(); ++i)
    if (open[i]) bits.set(static_cast<int64_t>(i));
  return bits;
}

// A random grid: open voxels with probability `fill`, then closed-walled boxes whose insides
// are open (caves unless a random gap in a wall lets the flood in).
std::vector<char> RandomGridWithCaves(const std::array<int, 3>& n, double fill, std::mt19937& rng) {
  std::vector<char> open(int64_t{n[0]} * n[1] * n[2]);
  std::bernoulli_distribution is_open(fill);
  for (char& v : open) v = is_open(rng) ? 1 : 0;
  const int64_t sy = n[0], sz = int64_t{n[0]} * n[1];
  for (int box = 0; box < 4; ++box) {
    int lo[3], hi[3];
    for (int a = 0; a < 3; ++a) {
      std::uniform_int_distribution<int> start(0, n[a] - 3);
      lo[a] = start(rng);
      std::uniform_int_distribution<int> end(lo[a] + 2, n[a] - 1);
      hi[a] = end(rng);
    }
    for (int z = lo[2]; z <= hi[2]; ++z)
      for (int y = lo[1]; y <= hi[1]; ++y)
        for (int x = lo[0]; x <= hi[0]; ++x) {
          const bool wall = x == lo[0] || x == hi[0] || y == lo[1] || y == hi[1] ||
                            z == lo[2] || z == hi[2];
          open[x + y * sy + z * sz] = wall ? 0 : 1;
        }
    if (box % 2 == 1) open[(lo[0] + hi[0]) / 2 + (lo[1] + hi[1]) / 2 * sy + lo[2] * sz] = 1;
  }
  return open;
}

TEST(BorderFlood, EqualsAPlainFloodOnRandomGridsWithCaves) {
  std::mt19937 rng(21);
  int64_t caves = 0, reached_total = 0;
  for (int trial = 0; trial < 300; ++trial) {
    std::uniform_int_distribution<int> side(3, trial < 250 ? 24 : 90);
    const std::array<int, 3> n = {side(rng), side(rng), side(rng)};
    const double fill = std::uniform_real_distribution<double>(0.2, 0.95)(rng);
    const std::vector<char> open = RandomGridWithCaves(n, fill, rng);
    const int64_t count = static_cast<int64_t>(open.size());
    const FlatBitset bits = OpenBits(open);
    const FlatBitset reached = FloodFromBorder(n, bits);
    std::vector<char> got(open.size());
    for (int64_t i = 0; i < count; ++i) got[i] = reached.test(i) ? 1 : 0;
    const std::vector<char> want = ReferenceFlood(n, open);
    ASSERT_EQ(got, want) << "trial " << trial << " dims " << n[0] << "x" << n[1] << "x" << n[2];
    for (int64_t i = 0; i < count; ++i) {
      caves += open[i] && !want[i];
      reached_total += want[i];
    }
    // No bit past the last voxel.
    if (count % 64 != 0) {
      EXPECT_EQ(reached.words()[reached.word_count() - 1] >> (count % 64), 0u);
    }
  }
  // The grids hold both: open voxels the flood reaches and open voxels it cannot.
  EXPECT_GT(caves, 1000);
  EXPECT_GT(reached_total, 1000);
}

// The slabs' flood against the one-thread flood: the same bits on 1 and 3 threads, for one
// slab, a few, and one a plane (every run that crosses a plane crosses a slab face), on random
// grids down to 3 voxels a side; and FloodFromBorder's own threaded path on a grid large
// enough to take it.
TEST(BorderFlood, SlabsGiveTheOneThreadFloodsBits) {
  std::mt19937 rng(22);
  int64_t caves = 0;
  for (int trial = 0; trial < 200; ++trial) {
    std::uniform_int_distribution<int> side(3, trial < 160 ? 20 : 70);
    const std::array<int, 3> n = {side(rng), side(rng), side(rng)};
    const double fill = std::uniform_real_distribution<double>(0.2, 0.95)(rng);
    const std::vector<char> open = RandomGridWithCaves(n, fill, rng);
    const int64_t count = static_cast<int64_t>(open.size());
    const FlatBitset bits = OpenBits(open);
    const FlatBitset serial = FloodFromBorder(n, bits, 1);
    for (int64_t i = 0; i < count; ++i) caves += open[i] && !serial.test(i);
    for (int threads : {1, 3})
      for (int slabs : {1, 2, 5, n[2]}) {
        const FlatBitset slabbed = FloodFromBorderOnSlabs(n, bits, threads, slabs);
        ASSERT_EQ(slabbed.word_count(), serial.word_count());
        for (size_t w = 0; w < serial.word_count(); ++w)
          ASSERT_EQ(slabbed.words()[w], serial.words()[w])
              << "trial " << trial << " dims " << n[0] << "x" << n[1] << "x" << n[2] << " threads "
              << threads << " slabs " << slabs << " word " << w;
      }
  }
  EXPECT_GT(caves, 1000);

  // 2^24 voxels and more: FloodFromBorder's threads take slabs.
  const std::array<int, 3> n = {260, 255, 261};
  const std::vector<char> open = RandomGridWithCaves(n, 0.9, rng);
  const int64_t count = static_cast<int64_t>(open.size());
  ASSERT_GE(count, int64_t{1} << 24);
  const FlatBitset bits = OpenBits(open);
  const FlatBitset serial = FloodFromBorder(n, bits, 1);
  const FlatBitset threaded = FloodFromBorder(n, bits, 3);
  for (size_t w = 0; w < serial.word_count(); ++w) ASSERT_EQ(threaded.words()[w], serial.words()[w]) << w;
  int64_t reached = serial.Count(), open_count = bits.Count();
  EXPECT_GT(reached, count / 2);
  EXPECT_LT(reached, open_count);
}

}  // namespace
}  // namespace membrane
