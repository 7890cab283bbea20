#include "core/engine/voxel_topology.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <optional>
#include <random>
#include <vector>

#include "core/engine/voxel_runs.h"
#include "gtest/gtest.h"

namespace membrane {
namespace {

// A grid of side n whose voxels satisfying `solid` (voxel-centre coordinates) are
// boundary soft, all others outside.
VoxelGrid Solid(int n, const std::function<bool(double, double, double)>& solid) {
  VoxelGrid g({n, n, n}, {0, 0, 0}, 1.0, OutsideState(0));
  for (int z = 1; z < n - 1; ++z)
    for (int y = 1; y < n - 1; ++y)
      for (int x = 1; x < n - 1; ++x)
        if (solid(x + 0.5, y + 0.5, z + 0.5)) g.set(Coord{x, y, z}, kBoundarySoft);
  return g;
}

TEST(VoxelTopology, BallHasOneShellOfGenusZero) {
  auto t = ComputeVoxelTopology(Solid(24, [](double x, double y, double z) {
    return std::hypot(x - 12, y - 12, z - 12) < 8;
  }));
  EXPECT_EQ(t.shells, 1);
  EXPECT_EQ(t.genus, std::vector<int>{0});
  EXPECT_EQ(t.cavities, 0);
}

TEST(VoxelTopology, SolidTorusHasGenusOne) {
  auto t = ComputeVoxelTopology(Solid(32, [](double x, double y, double z) {
    const double r = std::hypot(x - 16, y - 16) - 9;
    return std::hypot(r, z - 16) < 4;
  }));
  EXPECT_EQ(t.shells, 1);
  EXPECT_EQ(t.genus, std::vector<int>{1});
}

TEST(VoxelTopology, TwoBallsAreTwoShells) {
  auto t = ComputeVoxelTopology(Solid(32, [](double x, double y, double z) {
    return std::hypot(x - 9, y - 9, z - 16) < 6 || std::hypot(x - 23, y - 23, z - 16) < 6;
  }));
  EXPECT_EQ(t.shells, 2);
  EXPECT_EQ(t.genus, (std::vector<int>{0, 0}));
}

TEST(VoxelTopology, VoxelsTouchingAlongAnEdgeAreOneShell) {
  VoxelGrid g({6, 6, 6}, {0, 0, 0}, 1.0, OutsideState(0));
  g.set(Coord{2, 2, 2}, kBoundaryHard);
  g.set(Coord{3, 3, 2}, kBoundaryHard);
  auto t = ComputeVoxelTopology(g);
  EXPECT_EQ(t.shells, 1);
  EXPECT_EQ(t.genus, std::vector<int>{0});
}

TEST(VoxelTopology, RingOfVoxelsTouchingAtCornersHasGenusOne) {
  // Four voxels, each touching the next only at an edge, closing a loop around (3,3).
  VoxelGrid g({7, 7, 7}, {0, 0, 0}, 1.0, OutsideState(0));
  g.set(Coord{2, 3, 3}, kBoundaryHard);
  g.set(Coord{3, 2, 3}, kBoundaryHard);
  g.set(Coord{4, 3, 3}, kBoundaryHard);
  g.set(Coord{3, 4, 3}, kBoundaryHard);
  auto t = ComputeVoxelTopology(g);
  EXPECT_EQ(t.shells, 1);
  EXPECT_EQ(t.genus, std::vector<int>{1});
}

TEST(VoxelTopology, HollowBallReportsACavity) {
  auto t = ComputeVoxelTopology(Solid(24, [](double x, double y, double z) {
    const double r = std::hypot(x - 12, y - 12, z - 12);
    return r < 8 && r > 5;
  }));
  EXPECT_EQ(t.shells, 1);
  EXPECT_EQ(t.cavities, 1);
}

// The straightforward computation the run-based one must equal: a 26-neighbour DFS over voxels
// for the shells, the Euler table applied to every lattice vertex off the array border, and a
// 6-flood from the voxels next to the border layer for the cavities. Bounds are checked, so any
// grid will do.
struct Reference {
  VoxelTopology topo;
  std::vector<int32_t> label;
};

// 8 chi of one lattice vertex given its 8 voxels (bit dx + 2 dy + 4 dz): 8 V - 4 E + 2 F - C,
// the vertex itself, the 6 edges and 12 faces from it, each present when one voxel holding it is.
int ReferenceEuler8(int m) {
  auto has = [m](int dx, int dy, int dz) { return ((m >> (dx + 2 * dy + 4 * dz)) & 1) != 0; };
  int edges = 0, faces = 0, cubes = 0;
  for (int b = 0; b < 8; ++b) cubes += (m >> b) & 1;
  for (int a = 0; a < 3; ++a)
    for (int u = 0; u < 2; ++u)
      for (int v = 0; v < 2; ++v) {
        bool edge = false, face = false;  // edge: along a at side u; face: normal to a, quadrant (u, v)
        for (int p = 0; p < 2; ++p)
          for (int q = 0; q < 2; ++q) {
            int c[3];
            c[a] = u;
            c[(a + 1) % 3] = p;
            c[(a + 2) % 3] = q;
            if (v == 0) edge = edge || has(c[0], c[1], c[2]);
            c[a] = p;
            c[(a + 1) % 3] = u;
            c[(a + 2) % 3] = v;
            if (q == 0) face = face || has(c[0], c[1], c[2]);
          }
        edges += edge;
        faces += face;
      }
  return 8 * (m != 0) - 4 * edges + 2 * faces - cubes;
}

Reference BruteForce(const VoxelGrid& g) {
  Reference ref;
  const auto& d = g.dims();
  ref.label.assign(static_cast<size_t>(g.size()), -1);
  auto outside = [&](int x, int y, int z) { return IsOutside(g.at(Coord{x, y, z})); };
  std::vector<Coord> stack;
  for (int z = 0; z < d[2]; ++z)
    for (int y = 0; y < d[1]; ++y)
      for (int x = 0; x < d[0]; ++x) {
        const Coord seed{x, y, z};
        if (outside(x, y, z) || ref.label[static_cast<size_t>(g.Index(seed))] >= 0) continue;
        const int shell = ref.topo.shells++;
        ref.topo.voxels.push_back(0);
        ref.label[static_cast<size_t>(g.Index(seed))] = shell;
        stack.push_back(seed);
        while (!stack.empty()) {
          const Coord c = stack.back();
          stack.pop_back();
          ++ref.topo.voxels.back();
          for (int dz = -1; dz <= 1; ++dz)
            for (int dy = -1; dy <= 1; ++dy)
              for (int dx = -1; dx <= 1; ++dx) {
                const Coord n{c.x + dx, c.y + dy, c.z + dz};
                if (!g.Contains(n) || IsOutside(g.at(n)) || ref.label[static_cast<size_t>(g.Index(n))] >= 0) continue;
                ref.label[static_cast<size_t>(g.Index(n))] = shell;
                stack.push_back(n);
              }
        }
      }
  std::vector<int64_t> chi8(static_cast<size_t>(ref.topo.shells), 0);
  for (int z = 1; z < d[2]; ++z)
    for (int y = 1; y < d[1]; ++y)
      for (int x = 1; x < d[0]; ++x) {
        int m = 0, shell = -1;
        for (int b = 0; b < 8; ++b) {
          const Coord c{x - 1 + (b & 1), y - 1 + ((b >> 1) & 1), z - 1 + (b >> 2)};
          if (!IsOutside(g.at(c))) {
            m |= 1 << b;
            shell = ref.label[static_cast<size_t>(g.Index(c))];
          }
        }
        if (m != 0) chi8[static_cast<size_t>(shell)] += ReferenceEuler8(m);
      }
  for (int64_t c : chi8) ref.topo.genus.push_back(static_cast<int>(1 - c / 8));

  std::vector<uint8_t> reached(static_cast<size_t>(g.size()), 0);
  auto flood = [&](Coord seed) {
    reached[static_cast<size_t>(g.Index(seed))] = 1;
    stack.push_back(seed);
    while (!stack.empty()) {
      const Coord c = stack.back();
      stack.pop_back();
      for (int axis = 0; axis < 3; ++axis)
        for (int step : {-1, 1}) {
          Coord n = c;
          n[axis] += step;
          if (!g.Contains(n) || g.OnArrayBorder(n) || !IsOutside(g.at(n)) || reached[static_cast<size_t>(g.Index(n))])
            continue;
          reached[static_cast<size_t>(g.Index(n))] = 1;
          stack.push_back(n);
        }
    }
  };
  auto next_to_border = [&](const Coord& c) {
    return c.x == 1 || c.y == 1 || c.z == 1 || c.x == d[0] - 2 || c.y == d[1] - 2 || c.z == d[2] - 2;
  };
  for (int pass = 0; pass < 2; ++pass)
    for (int z = 0; z < d[2]; ++z)
      for (int y = 0; y < d[1]; ++y)
        for (int x = 0; x < d[0]; ++x) {
          const Coord c{x, y, z};
          if (g.OnArrayBorder(c) || !IsOutside(g.at(c)) || reached[static_cast<size_t>(g.Index(c))]) continue;
          if (pass == 0 && next_to_border(c)) flood(c);
          if (pass == 1) {
            ++ref.topo.cavities;
            flood(c);
          }
        }
  return ref;
}

// A random solid in a grid with an outside border layer: a union of balls and solid tori with
// balls carved out (holes, tunnels, cavities), sprinkled with single voxels flipped either way
// (diagonal-only contacts, lone voxels, pockets).
VoxelGrid RandomSolid(std::mt19937& rng) {
  std::uniform_int_distribution<int> side(3, 14);
  const std::array<int, 3> dims{side(rng), side(rng), side(rng)};
  VoxelGrid g(dims, {0, 0, 0}, 1.0, OutsideState(0));
  auto uniform = [&rng](double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); };
  auto centre = [&](int axis) { return uniform(0, dims[static_cast<size_t>(axis)]); };
  struct Shape {
    int kind;  // 0 ball added, 1 torus added, 2 ball removed
    double x, y, z, r, t;
  };
  std::vector<Shape> shapes;
  const int count = std::uniform_int_distribution<int>(0, 6)(rng);
  for (int i = 0; i < count; ++i)
    shapes.push_back({std::uniform_int_distribution<int>(0, 2)(rng), centre(0), centre(1), centre(2), uniform(0.5, 5),
                      uniform(0.5, 2)});
  const double noise = uniform(0, 0.3);
  for (int z = 1; z < dims[2] - 1; ++z)
    for (int y = 1; y < dims[1] - 1; ++y)
      for (int x = 1; x < dims[0] - 1; ++x) {
        const double px = x + 0.5, py = y + 0.5, pz = z + 0.5;
        bool solid = false;
        for (const Shape& s : shapes) {
          const double r = std::hypot(px - s.x, py - s.y, pz - s.z);
          if (s.kind == 0 && r < s.r) solid = true;
          if (s.kind == 1 && std::hypot(std::hypot(px - s.x, py - s.y) - s.r, pz - s.z) < s.t) solid = true;
          if (s.kind == 2 && r < s.r) solid = false;
        }
        if (uniform(0, 1) < noise) solid = !solid;
        if (solid) g.set(Coord{x, y, z}, uniform(0, 1) < 0.5 ? kBoundarySoft : kInsideHard);
        else g.set(Coord{x, y, z}, OutsideState(std::uniform_int_distribution<int>(0, 127)(rng)));
      }
  return g;
}

TEST(VoxelTopology, MatchesBruteForceOnRandomGrids) {
  std::mt19937 rng(20261128);
  int with_cavities = 0, with_genus = 0, with_several_shells = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const VoxelGrid g = RandomSolid(rng);
    const Reference ref = BruteForce(g);
    const VoxelTopology t = ComputeVoxelTopology(g);
    ASSERT_EQ(t.shells, ref.topo.shells) << "trial " << trial;
    ASSERT_EQ(t.genus, ref.topo.genus) << "trial " << trial;
    ASSERT_EQ(t.voxels, ref.topo.voxels) << "trial " << trial;
    ASSERT_EQ(t.cavities, ref.topo.cavities) << "trial " << trial;
    std::vector<int32_t> label;
    ASSERT_EQ(LabelShells(g, label), ref.topo.shells) << "trial " << trial;
    ASSERT_EQ(label, ref.label) << "trial " << trial;
    with_cavities += ref.topo.cavities > 0;
    with_several_shells += ref.topo.shells > 1;
    for (int genus : ref.topo.genus) with_genus += genus != 0;
  }
  // The random solids exercise what the comparison is for.
  EXPECT_GT(with_cavities, 100);
  EXPECT_GT(with_several_shells, 100);
  EXPECT_GT(with_genus, 100);
}

// A grid over NonOutsideRuns' split size (2^24 voxels): balls and solid tori with random
// voxels flipped, so that rows hold many runs and several slabs hold shells that cross them.
VoxelGrid LargeRandomSolid() {
  const std::array<int, 3> dims = {260, 258, 256};
  VoxelGrid g(dims, {0, 0, 0}, 1.0, OutsideState(0));
  std::mt19937 rng(20261205);
  std::uniform_real_distribution<double> uniform(0, 1);
  for (int z = 1; z < dims[2] - 1; ++z)
    for (int y = 1; y < dims[1] - 1; ++y)
      for (int x = 1; x < dims[0] - 1; ++x) {
        const double ball = std::hypot(x - 70.0, y - 80.0, z - 90.0);
        const double ring = std::hypot(std::hypot(x - 170.0, z - 140.0) - 60, y - 150.0);
        bool solid = ball < 50 || ring < 18;
        if (uniform(rng) < 0.02) solid = !solid;
        if (solid) g.set(Coord{x, y, z}, uniform(rng) < 0.5 ? kBoundarySoft : kInsideHard);
      }
  return g;
}

TEST(VoxelTopology, TheSameRunsAndTopologyOnAnyThreadCount) {
  const VoxelGrid g = LargeRandomSolid();
  ASSERT_GE(g.size(), int64_t{1} << 24);
  const VoxelRuns one = NonOutsideRuns(g);
  const VoxelTopology expected = ComputeVoxelTopology(g);
  ASSERT_GT(one.runs.size(), 100000u);
  ASSERT_GT(expected.shells, 100);
  for (int threads : {2, 3}) {
    const VoxelRuns split = NonOutsideRuns(g, threads);
    EXPECT_EQ(split.dims, one.dims) << threads << " threads";
    EXPECT_EQ(split.row_begin, one.row_begin) << threads << " threads";
    ASSERT_EQ(split.runs.size(), one.runs.size()) << threads << " threads";
    EXPECT_TRUE(std::equal(split.runs.begin(), split.runs.end(), one.runs.begin(),
                           [](const VoxelRun& a, const VoxelRun& b) {
                             return a.begin == b.begin && a.end == b.end &&
                                    a.component == b.component;
                           }))
        << threads << " threads";
    const std::optional<VoxelTopology> t = ComputeVoxelTopology(g, CancelToken::Never(), threads);
    ASSERT_TRUE(t.has_value());
    EXPECT_EQ(t->shells, expected.shells) << threads << " threads";
    EXPECT_EQ(t->genus, expected.genus) << threads << " threads";
    EXPECT_EQ(t->voxels, expected.voxels) << threads << " threads";
    EXPECT_EQ(t->cavities, expected.cavities) << threads << " threads";
  }
}

int64_t EulerOf(const VoxelTopology& t) {
  int64_t chi = 0;
  for (int genus : t.genus) chi += 1 - genus;
  return chi;
}

// A carve counted around the carved voxels gives the whole grid's answer: the Euler change
// always, the shell count when it says kept or removed, no cavity when it touches the outside of
// a grid without any. Carves: random face paths of 1 to 8 non-outside voxels off the border.
TEST(VoxelTopology, CarveCountedLocallyMatchesTheWholeGrid) {
  std::mt19937 rng(20261203);
  int kept = 0, removed = 0, unknown = 0, handles = 0, splits = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    VoxelGrid g = RandomSolid(rng);
    std::vector<int64_t> solid;
    for (int64_t i = 0; i < g.size(); ++i)
      if (!IsOutside(g.at(i))) solid.push_back(i);
    if (solid.empty()) continue;
    std::vector<int64_t> carved = {solid[std::uniform_int_distribution<size_t>(0, solid.size() - 1)(rng)]};
    const int length = std::uniform_int_distribution<int>(1, 8)(rng);
    for (int step = 1; step < length; ++step) {
      const Coord c = g.CoordOf(carved.back());
      Coord n = c;
      n[std::uniform_int_distribution<int>(0, 2)(rng)] += std::uniform_int_distribution<int>(0, 1)(rng) * 2 - 1;
      if (g.OnArrayBorder(n) || !g.Contains(n) || IsOutside(g.at(n))) break;
      if (std::find(carved.begin(), carved.end(), g.Index(n)) != carved.end()) break;
      carved.push_back(g.Index(n));
    }
    const int margin = std::uniform_int_distribution<int>(0, 4)(rng);
    const CarveTopologyChange change = CountCarveLocally(g, carved, margin);
    const VoxelTopology before = ComputeVoxelTopology(g);
    for (int64_t i : carved) g.set(i, OutsideState(0));
    const VoxelTopology after = ComputeVoxelTopology(g);
    ASSERT_EQ(change.euler_change, EulerOf(after) - EulerOf(before)) << "trial " << trial;
    if (change.shells == CarveTopologyChange::Shells::kKept) {
      ASSERT_EQ(after.shells, before.shells) << "trial " << trial;
      ++kept;
      handles += change.euler_change < 0;
    } else if (change.shells == CarveTopologyChange::Shells::kRemoved) {
      ASSERT_EQ(after.shells, before.shells - 1) << "trial " << trial;
      ++removed;
    } else {
      ++unknown;
      splits += after.shells > before.shells;
    }
    if (before.cavities == 0 && change.touches_outside) {
      ASSERT_EQ(after.cavities, 0) << "trial " << trial;
    }
  }
  // Every answer occurs, and carves that add a handle or split a shell are among them.
  EXPECT_GT(kept, 300);
  EXPECT_GT(removed, 10);
  EXPECT_GT(unknown, 30);
  EXPECT_GT(handles, 30);
  EXPECT_GT(splits, 10);
}

// A thin ring cut once: its two ends are joined only around the ring, so a cube smaller than
// the ring cannot tell a cut from a split, and one holding the ring can.
TEST(VoxelTopology, RingCutIsKnownKeptOnlyInACubeHoldingTheRing) {
  VoxelGrid g = Solid(32, [](double x, double y, double z) {
    return std::abs(std::hypot(x - 16, y - 16) - 10) < 0.8 && std::abs(z - 16.5) < 0.6;
  });
  ASSERT_EQ(ComputeVoxelTopology(g).genus, std::vector<int>{1});
  // The ring is two voxels wide where it crosses y = 16 on the +x side.
  const std::vector<int64_t> carved = {g.Index(25, 16, 16), g.Index(26, 16, 16)};
  for (int64_t i : carved) ASSERT_FALSE(IsOutside(g.at(i)));
  ASSERT_TRUE(IsOutside(g.at(g.Index(24, 16, 16))));
  ASSERT_TRUE(IsOutside(g.at(g.Index(27, 16, 16))));
  EXPECT_EQ(CountCarveLocally(g, carved, 3).shells, CarveTopologyChange::Shells::kUnknown);
  const CarveTopologyChange whole = CountCarveLocally(g, carved, 24);
  EXPECT_EQ(whole.shells, CarveTopologyChange::Shells::kKept);
  EXPECT_EQ(whole.euler_change, 1);  // genus 1 -> 0: an arc
  EXPECT_TRUE(whole.touches_outside);
}

}  // namespace
}  // namespace membrane
