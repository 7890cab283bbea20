#include "core/mesh/fan_embedding.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <random>
#include <utility>
#include <vector>

#include "core/mesh/triangle_intersection.h"
#include "core/mesh/vertex_stars.h"
#include "gtest/gtest.h"
#include "tests/mesh/mesh_builders.h"

namespace membrane {
namespace {

using testing::CubeMesh;

// A ring of k points around the origin in the z = 0 plane, at the given angles (radians).
std::vector<Vec3d> Ring(const std::vector<double>& angles, double radius = 1) {
  std::vector<Vec3d> ring;
  for (double a : angles) ring.push_back({radius * std::cos(a), radius * std::sin(a), 0});
  return ring;
}

std::vector<double> EvenAngles(int k, double turns = 1) {
  std::vector<double> angles;
  for (int i = 0; i < k; ++i) angles.push_back(2 * M_PI * turns * i / k);
  return angles;
}

// The exhaustive test the proof stands in for: any two faces of the fan overlapping.
bool AnyPairOverlaps(const Vec3d& centre, const std::vector<Vec3d>& ring) {
  const int32_t k = static_cast<int32_t>(ring.size());
  auto face = [&](int32_t i) {
    return std::pair<std::array<int32_t, 3>, Triangle3d>{{0, 1 + i, 1 + (i + 1) % k},
                                                         {centre, ring[i], ring[(i + 1) % k]}};
  };
  for (int32_t i = 0; i < k; ++i)
    for (int32_t j = i + 1; j < k; ++j) {
      const auto [ia, a] = face(i);
      const auto [ib, b] = face(j);
      if (MeshTrianglesIntersect(ia, a, ib, b)) return true;
    }
  return false;
}

TEST(FanEmbedding, FlatHexagonIsEmbedded) {
  EXPECT_TRUE(FanIsEmbedded({0, 0, 0}, Ring(EvenAngles(6))));
}

TEST(FanEmbedding, ConeAndSaddleAreEmbedded) {
  std::vector<Vec3d> cone = Ring(EvenAngles(7)), saddle = Ring(EvenAngles(8));
  for (Vec3d& p : cone) p[2] = -0.8;
  for (size_t i = 0; i < saddle.size(); ++i) saddle[i][2] = i % 2 ? 0.4 : -0.4;
  EXPECT_TRUE(FanIsEmbedded({0, 0, 0}, cone));
  EXPECT_TRUE(FanIsEmbedded({0, 0, 0}, saddle));
}

TEST(FanEmbedding, ClockwiseRingIsEmbeddedSeenFromBelow) {
  // Only the relative orientation counts: the normals' sum then points down.
  std::vector<double> angles = EvenAngles(6);
  for (double& a : angles) a = -a;
  EXPECT_TRUE(FanIsEmbedded({0, 0, 0}, Ring(angles)));
}

TEST(FanEmbedding, RingWoundTwiceIsNotProven) {
  // Every sector a third of a turn, counter-clockwise, but the ring goes round twice: the
  // faces overlap although each one alone is positively oriented.
  const std::vector<Vec3d> ring = Ring(EvenAngles(6, 2));
  EXPECT_TRUE(AnyPairOverlaps({0, 0, 0}, ring));
  EXPECT_FALSE(FanIsEmbedded({0, 0, 0}, ring));
}

TEST(FanEmbedding, FoldedFaceIsNotProven) {
  // One ring vertex pulled across its neighbour: that sector turns clockwise.
  std::vector<double> angles = EvenAngles(6);
  angles[2] = angles[1] - 0.3;
  EXPECT_FALSE(FanIsEmbedded({0, 0, 0}, Ring(angles)));
}

TEST(FanEmbedding, PointSymmetricFlatFanIsEmbedded) {
  // Opposite sectors exactly point-symmetric and coplanar: a configuration met on real scans.
  EXPECT_TRUE(FanIsEmbedded({0.5f, 0.25f, 0.125f}, {{1.5f, 0.25f, 0.125f},
                                                    {1.0f, 1.25f, 0.125f},
                                                    {-0.5f, 0.25f, 0.125f},
                                                    {0.0f, -0.75f, 0.125f}}));
}

TEST(FanEmbedding, NeverProvesAFanWhosePairsOverlap) {
  // Random fans, from gentle to wild: whenever the proof concludes, the exhaustive test agrees;
  // and it does conclude on most gentle ones.
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(-1, 1);
  int proven = 0, gentle = 0, gentle_proven = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const int k = 3 + trial % 8;
    const double wild = (trial % 5) * 0.5;
    std::vector<double> angles = EvenAngles(k);
    for (double& a : angles) a += wild * unit(rng);
    std::vector<Vec3d> ring = Ring(angles);
    for (Vec3d& p : ring)
      for (double& c : p) c += (0.2 + wild) * unit(rng);
    const Vec3d centre{0.1 * unit(rng), 0.1 * unit(rng), 0.1 * unit(rng)};
    const bool ok = FanIsEmbedded(centre, ring);
    if (ok) {
      ++proven;
      ASSERT_FALSE(AnyPairOverlaps(centre, ring)) << "trial " << trial;
    }
    if (wild == 0) {
      ++gentle;
      gentle_proven += ok;
    }
  }
  EXPECT_GT(proven, 1000);
  EXPECT_GT(gentle_proven, gentle / 2);
}

TEST(FanEmbedding, CubeVerticesHaveClosedFansInFaceOrder) {
  const TriangleMesh cube = CubeMesh();
  const MeshFans fans(cube);
  for (int32_t v = 0; v < static_cast<int32_t>(cube.vertices.size()); ++v) {
    const auto ring = fans.ring(v);
    ASSERT_GE(ring.size(), 3u) << "vertex " << v;
    // (v, ring[i], ring[i+1]) is a face of the cube, up to rotation.
    for (size_t i = 0; i < ring.size(); ++i) {
      const int32_t a = ring[i], b = ring[(i + 1) % ring.size()];
      bool found = false;
      for (const auto& f : cube.faces)
        for (int r = 0; r < 3; ++r)
          found = found || (f[r] == v && f[(r + 1) % 3] == a && f[(r + 2) % 3] == b);
      EXPECT_TRUE(found) << "vertex " << v << " step " << i;
    }
  }
}

TEST(FanEmbedding, DuplicatedFaceLeavesItsVerticesWithoutFan) {
  TriangleMesh cube = CubeMesh();
  cube.faces.push_back(cube.faces[0]);
  const MeshFans fans(cube);
  for (int32_t v : cube.faces[0]) EXPECT_TRUE(fans.ring(v).empty()) << "vertex " << v;
}

TEST(FanEmbedding, TwoFansGluedAtAVertexGiveNoRing) {
  // Two tetrahedra sharing only vertex 0: its faces form two cycles of three.
  TriangleMesh m;
  m.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {-1, 0, 0}, {0, -1, 0}, {0, 0, -1}};
  m.faces = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3},
             {0, 4, 5}, {0, 6, 4}, {0, 5, 6}, {4, 6, 5}};
  const MeshFans fans(m);
  EXPECT_TRUE(fans.ring(0).empty());
  EXPECT_EQ(fans.ring(1).size(), 3u);
}

// Each vertex's ring walked straight from its faces' steps in face index order (a face listing
// the vertex twice gives a step for each of its corners): empty when its faces make no single
// closed fan.
std::vector<std::vector<int32_t>> RingsWalkedFromFaces(const TriangleMesh& mesh) {
  std::vector<std::vector<std::pair<int32_t, int32_t>>> steps(mesh.vertices.size());
  for (const auto& f : mesh.faces)
    for (int k = 0; k < 3; ++k)
      steps[static_cast<size_t>(f[k])].push_back({f[(k + 1) % 3], f[(k + 2) % 3]});
  std::vector<std::vector<int32_t>> rings(mesh.vertices.size());
  for (size_t v = 0; v < steps.size(); ++v) {
    const auto& s = steps[v];
    const size_t n = s.size();
    bool fan = n >= 3;
    for (size_t i = 0; fan && i < n; ++i)
      for (size_t j = i + 1; fan && j < n; ++j)
        fan = s[i].first != s[j].first && s[i].second != s[j].second;
    std::vector<int32_t> ring;
    int32_t a = fan ? s[0].first : -1;
    for (size_t visited = 0; fan && visited < n; ++visited) {
      if (visited > 0 && a == s[0].first) fan = false;
      if (!fan) break;
      ring.push_back(a);
      const auto next =
          std::find_if(s.begin(), s.end(), [&](const auto& step) { return step.first == a; });
      fan = next != s.end();
      if (fan) a = next->second;
    }
    if (fan && a == s[0].first) rings[v] = std::move(ring);
  }
  return rings;
}

TEST(FanEmbedding, RingsFromStarsOnRangesAreTheWalksFromTheFaces) {
  // A closed 300 x 250 torus grid (75,000 vertices: ranges on the threads), its faces in a
  // random order, with a duplicated face, faces listing a vertex twice and a second fan glued
  // at a vertex; every ring against the walk from the faces, on 1 to 3 threads.
  constexpr int32_t kRows = 300, kCols = 250;
  auto id = [&](int32_t r, int32_t c) { return (r % kRows) * kCols + (c % kCols); };
  TriangleMesh mesh;
  mesh.vertices.resize(static_cast<size_t>(kRows) * kCols, Point3f{0, 0, 0});
  for (int32_t r = 0; r < kRows; ++r)
    for (int32_t c = 0; c < kCols; ++c) {
      mesh.faces.push_back({id(r, c), id(r + 1, c), id(r + 1, c + 1)});
      mesh.faces.push_back({id(r, c), id(r + 1, c + 1), id(r, c + 1)});
    }
  std::mt19937 rng(3);
  std::shuffle(mesh.faces.begin(), mesh.faces.end(), rng);
  mesh.faces.push_back(mesh.faces[10]);
  mesh.faces.push_back({id(5, 5), id(5, 5), id(5, 6)});
  mesh.faces.push_back({id(70, 9), id(71, 9), id(70, 9)});
  mesh.faces.push_back({id(200, 3), id(200, 3), id(200, 3)});
  mesh.faces.push_back({id(150, 100), id(10, 10), id(20, 20)});
  mesh.faces.push_back({id(150, 100), id(20, 20), id(30, 30)});
  mesh.faces.push_back({id(150, 100), id(30, 30), id(10, 10)});
  const int32_t nv = static_cast<int32_t>(mesh.vertices.size());
  const std::vector<std::vector<int32_t>> expected = RingsWalkedFromFaces(mesh);
  int32_t fans = 0;
  for (const auto& ring : expected) fans += !ring.empty();
  ASSERT_GT(fans, nv - 40);
  ASSERT_LT(fans, nv);
  for (int threads : {1, 2, 3}) {
    const MeshFans from_stars(mesh.faces, FacesAroundVertices(mesh.faces, nv, threads), threads);
    for (int32_t v = 0; v < nv; ++v) {
      const auto ring = from_stars.ring(v);
      ASSERT_EQ(std::vector<int32_t>(ring.begin(), ring.end()), expected[static_cast<size_t>(v)])
          << "vertex " << v << ", " << threads << " threads";
    }
  }
  const MeshFans from_mesh(mesh);
  for (int32_t v = 0; v < nv; ++v) {
    const auto ring = from_mesh.ring(v);
    ASSERT_EQ(std::vector<int32_t>(ring.begin(), ring.end()), expected[static_cast<size_t>(v)])
        << "vertex " << v;
  }
}

}  // namespace
}  // namespace membrane
