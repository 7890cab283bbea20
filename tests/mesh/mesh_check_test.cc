#include "core/mesh/mesh_check.h"

#include <algorithm>
#include <cmath>

#include <iostream>
#include <utility>
#include <vector>

#include "core/mesh/self_intersection.h"
#include "core/mesh/triangle_intersection.h"
#include "gtest/gtest.h"
#include "tests/mesh/mesh_builders.h"

namespace membrane {
namespace {

using testing::Concat;
using testing::CubeMesh;
using testing::TorusMesh;

// Two tori of `rings` x `segments` crossing along a ring, and a third, a little over a third
// as fine, touching the second: many crossing pairs, in cells shared by the three.
TriangleMesh CrossingTori(int rings, int segments) {
  TriangleMesh a = TorusMesh(rings, segments, 1.0f, 0.3f);
  TriangleMesh b = TorusMesh(rings, segments, 1.0f, 0.3f);
  TriangleMesh c = TorusMesh(rings * 3 / 10, segments * 3 / 10, 0.5f, 0.2f);
  for (auto& v : b.vertices) v[0] += 0.3f;
  for (auto& v : c.vertices) v[2] += 0.5f;
  return Concat(Concat(a, b), c);
}

TEST(MeshCheck, AcceptsClosedOutwardCube) {
  const MeshReport r = CheckMesh(CubeMesh());
  EXPECT_EQ(r.vertices, 8);
  EXPECT_EQ(r.faces, 12);
  EXPECT_TRUE(r.closed);
  EXPECT_TRUE(r.manifold);
  EXPECT_TRUE(r.oriented);
  EXPECT_TRUE(r.positive_volume);
  EXPECT_NEAR(r.volume, 1.0, 1e-6);
  EXPECT_EQ(r.self_intersections, 0);
  EXPECT_EQ(r.degenerate_faces, 0);
  EXPECT_EQ(r.shells, 1);
  EXPECT_EQ(r.genus, std::vector<int>{0});
}

TEST(MeshCheck, DetectsOpenEdge) {
  TriangleMesh m = CubeMesh();
  m.faces.pop_back();
  const MeshReport r = CheckMesh(m);
  EXPECT_FALSE(r.closed);
  EXPECT_EQ(r.boundary_edges, 3);
  EXPECT_TRUE(r.manifold);
  EXPECT_EQ(r.genus, std::vector<int>{-1});
}

TEST(MeshCheck, DetectsFlippedFace) {
  TriangleMesh m = CubeMesh();
  std::swap(m.faces[3][1], m.faces[3][2]);
  const MeshReport r = CheckMesh(m);
  EXPECT_TRUE(r.closed);
  EXPECT_FALSE(r.oriented);
  EXPECT_EQ(r.misoriented_edges, 3);
}

TEST(MeshCheck, DetectsInwardNormals) {
  TriangleMesh m = CubeMesh();
  for (auto& f : m.faces) std::swap(f[1], f[2]);
  const MeshReport r = CheckMesh(m);
  EXPECT_TRUE(r.oriented);
  EXPECT_FALSE(r.positive_volume);
  EXPECT_NEAR(r.volume, -1.0, 1e-6);
}

TEST(MeshCheck, DetectsSelfIntersection) {
  const MeshReport r = CheckMesh(Concat(CubeMesh(), CubeMesh({0.5f, 0.5f, 0.5f})));
  EXPECT_TRUE(r.closed);
  EXPECT_EQ(r.shells, 2);
  EXPECT_GT(r.self_intersections, 0);
}

TEST(MeshCheck, CancelStopsTheSelfIntersectionSearchEarly) {
  // Two fine tori crossing each other everywhere along a ring: many cells, many crossings.
  TriangleMesh a = TorusMesh(400, 200, 1.0f, 0.3f);
  TriangleMesh b = TorusMesh(400, 200, 1.0f, 0.3f);
  for (auto& v : b.vertices) v[0] += 0.3f;
  const TriangleMesh both = Concat(a, b);
  const MeshReport full = CheckMesh(both);
  ASSERT_GT(full.self_intersections, 100);
  CancelToken cancel;
  cancel.Cancel();
  const MeshReport cancelled = CheckMesh(both, cancel);
  EXPECT_LT(cancelled.self_intersections, full.self_intersections);
}

TEST(MeshCheck, SearchFindsTheSamePairsOnAnyThreadCount) {
  // Two tori crossing along a ring, and a third touching the second: the cells are shared out
  // among the threads, and the pairs must come back the same, each once, in order.
  const TriangleMesh all = CrossingTori(200, 100);
  const auto one = FindIntersectingFaces(all, CancelToken::Never(), 1);
  ASSERT_GT(one.size(), 100u);
  EXPECT_TRUE(std::is_sorted(one.begin(), one.end()));
  EXPECT_TRUE(std::adjacent_find(one.begin(), one.end()) == one.end());
  for (int threads : {2, 3, 7}) {
    EXPECT_EQ(FindIntersectingFaces(all, CancelToken::Never(), threads), one)
        << threads << " threads";
    EXPECT_EQ(CheckMesh(all, CancelToken::Never(), threads).self_intersections,
              static_cast<int64_t>(one.size()));
  }
  // The search around a few marked faces, the fit's, splits the same way.
  std::vector<char> dirty(all.faces.size(), 0);
  for (size_t f = 0; f < dirty.size(); f += 97) dirty[f] = 1;
  const auto near_one = FindIntersectingFacesNear(all, dirty, 1);
  EXPECT_EQ(FindIntersectingFacesNear(all, dirty, 4), near_one);
}

TEST(MeshCheck, SearchFindsThePairsThatTestingEveryPairFinds) {
  // The search makes each face's triangle and plane in each cell where it is first tested (a
  // face spans several cells): its pairs must be those of MeshTrianglesIntersect over every
  // pair of faces, here 3,344.
  const TriangleMesh all = CrossingTori(40, 20);
  auto triangle = [&](int32_t f) {
    const auto& idx = all.faces[f];
    return Triangle3d{ToVec3d(all.vertices[idx[0]]), ToVec3d(all.vertices[idx[1]]),
                      ToVec3d(all.vertices[idx[2]])};
  };
  std::vector<std::pair<int32_t, int32_t>> every;
  const int32_t nf = static_cast<int32_t>(all.faces.size());
  for (int32_t i = 0; i < nf; ++i)
    for (int32_t j = i + 1; j < nf; ++j)
      if (MeshTrianglesIntersect(all.faces[i], triangle(i), all.faces[j], triangle(j)))
        every.emplace_back(i, j);
  ASSERT_GT(every.size(), 50u);
  for (int threads : {1, 2})
    EXPECT_EQ(FindIntersectingFaces(all, CancelToken::Never(), threads), every)
        << threads << " threads";
}

TEST(MeshCheck, SearchFindsEveryPairInCellsCrowdedWithSmallFaces) {
  // The cells are twice the mean face wide. Where much smaller faces crowd into one (a cap
  // folded into a patch), the search splits the cell's faces into width classes; the faces
  // wider than every class are tried against all. Here two crossing tori of faces about
  // 0.0014 wide, a torus of faces about 0.004 wide through them and a cube of 0.05 around
  // them sit on a torus of faces about 0.2 wide: the mean (0.019) makes cells of 0.039, and
  // the 7,200 small faces (and the 1,600 smaller ones below) lie within a cube of 0.03, so
  // some cell holds over 1,100 of them.
  auto moved = [](TriangleMesh m, float dx, float dy, float dz) {
    for (auto& v : m.vertices) v[0] += dx, v[1] += dy, v[2] += dz;
    return m;
  };
  const float x = 1.3f;
  TriangleMesh all = TorusMesh(40, 20, 1.0f, 0.3f);
  all = Concat(all, moved(TorusMesh(60, 30, 0.01f, 0.003f), x, 0, 0));
  all = Concat(all, moved(TorusMesh(60, 30, 0.01f, 0.003f), x + 0.003f, 0, 0.002f));
  all = Concat(all, moved(TorusMesh(40, 20, 0.02f, 0.006f), x, 0.004f, 0));
  all = Concat(all, CubeMesh({x - 0.025f, -0.025f, -0.025f}, 0.05f));
  // Two crossing tori of 800 faces about 0.00005 wide across the first small one's outer
  // edge: in the cells beside them the smallest width class's sub-cells (about 0.0024 wide)
  // hold them among the small faces, over 512 members each.
  all = Concat(all, moved(TorusMesh(40, 20, 0.0002f, 0.00006f), x + 0.013f, 0, 0));
  all = Concat(all, moved(TorusMesh(40, 20, 0.0002f, 0.00006f), x + 0.01306f, 0, 0.00004f));
  const int32_t nf = static_cast<int32_t>(all.faces.size());
  auto box = [&](int32_t f) {
    std::array<float, 3> lo{1e30f, 1e30f, 1e30f}, hi{-1e30f, -1e30f, -1e30f};
    for (int32_t v : all.faces[f])
      for (int k = 0; k < 3; ++k) {
        lo[k] = std::min(lo[k], all.vertices[v][k]);
        hi[k] = std::max(hi[k], all.vertices[v][k]);
      }
    return std::pair{lo, hi};
  };
  double extent_sum = 0;
  int crowded = 0;
  for (int32_t f = 0; f < nf; ++f) {
    const auto [lo, hi] = box(f);
    extent_sum += std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
    const float xc = x + 0.0015f, h = 0.015f;
    crowded += lo[0] >= xc - h && hi[0] <= xc + h && std::abs(lo[1]) <= h &&
               std::abs(hi[1]) <= h && std::abs(lo[2]) <= h && std::abs(hi[2]) <= h;
  }
  ASSERT_LE(0.03, 2 * extent_sum / nf);  // a cube of 0.03 spans at most 8 cells
  ASSERT_GE(crowded, 8 * 513);
  auto triangle = [&](int32_t f) {
    const auto& idx = all.faces[f];
    return Triangle3d{ToVec3d(all.vertices[idx[0]]), ToVec3d(all.vertices[idx[1]]),
                      ToVec3d(all.vertices[idx[2]])};
  };
  std::vector<std::pair<int32_t, int32_t>> every;
  for (int32_t i = 0; i < nf; ++i) {
    const auto [lo_i, hi_i] = box(i);
    for (int32_t j = i + 1; j < nf; ++j) {
      const auto [lo_j, hi_j] = box(j);
      bool overlap = true;
      for (int k = 0; k < 3; ++k) overlap &= lo_i[k] <= hi_j[k] && lo_j[k] <= hi_i[k];
      if (overlap && MeshTrianglesIntersect(all.faces[i], triangle(i), all.faces[j], triangle(j)))
        every.emplace_back(i, j);
    }
  }
  ASSERT_GT(every.size(), 1000u);
  for (int threads : {1, 3})
    EXPECT_EQ(FindIntersectingFaces(all, CancelToken::Never(), threads), every)
        << threads << " threads";
  // Around every seventh face, as the caps' back-off searches.
  std::vector<char> dirty(all.faces.size(), 0);
  for (size_t f = 0; f < dirty.size(); f += 7) dirty[f] = 1;
  std::vector<std::pair<int32_t, int32_t>> near;
  for (const auto& [a, b] : every)
    if (dirty[a] || dirty[b]) near.emplace_back(a, b);
  EXPECT_EQ(FindIntersectingFacesNear(all, dirty, 2), near);
}

TEST(MeshCheck, SearchNearDirtyFacesSkipsFarRunsWithoutMissingPairs) {
  // The run boxes kept between searches, as the fit keeps them while it moves vertices: each
  // search must find what the search without them finds. Two tori, one above the other with a
  // gap of 0.02 between them at (1, 0, 0.31): the first search sees them apart; then the
  // lower one's top vertex there moves up (its faces are dirty once, clean after), then the
  // upper one's bottom vertex moves down, and the two fans cross, the lower one's out of the
  // box its run had when the runs were first made.
  TriangleMesh upper = TorusMesh(200, 100, 1.0f, 0.3f);
  for (auto& v : upper.vertices) v[2] += 0.62f;
  TriangleMesh mesh = Concat(TorusMesh(200, 100, 1.0f, 0.3f), upper);
  auto nearest = [&mesh](const Point3f& p) {
    int32_t best = 0;
    double best_d2 = 1e30;
    for (size_t v = 0; v < mesh.vertices.size(); ++v) {
      double d2 = 0;
      for (int k = 0; k < 3; ++k) d2 += std::pow(mesh.vertices[v][k] - p[k], 2);
      if (d2 < best_d2) best_d2 = d2, best = static_cast<int32_t>(v);
    }
    return best;
  };
  const int32_t low = nearest({1.0f, 0.0f, 0.3f}), high = nearest({1.0f, 0.0f, 0.32f});
  FaceBlockBoxes blocks;
  std::vector<char> dirty(mesh.faces.size(), 1);
  ASSERT_TRUE(FindIntersectingFacesNear(mesh, dirty, 1, &blocks).empty());
  for (const auto& [v, dz] : {std::pair{low, 0.015f}, std::pair{high, -0.015f}}) {
    mesh.vertices[v][2] += dz;
    std::fill(dirty.begin(), dirty.end(), 0);
    for (size_t f = 0; f < mesh.faces.size(); ++f)
      for (int32_t u : mesh.faces[f])
        if (u == v) dirty[f] = 1;
    EXPECT_EQ(FindIntersectingFacesNear(mesh, dirty, 2, &blocks),
              FindIntersectingFacesNear(mesh, dirty, 1));
  }
  EXPECT_FALSE(FindIntersectingFaces(mesh).empty());
}

TEST(MeshCheck, CountsTouchingShellsAsIntersecting) {
  // Two cubes sharing a face plane but no vertex ids: touching is a self-intersection.
  const MeshReport r = CheckMesh(Concat(CubeMesh(), CubeMesh({1, 0, 0})));
  EXPECT_GT(r.self_intersections, 0);
}

TEST(MeshCheck, SeparateShellsDoNotIntersect) {
  const MeshReport r = CheckMesh(Concat(CubeMesh(), CubeMesh({1.5f, 0, 0})));
  EXPECT_EQ(r.self_intersections, 0);
  EXPECT_EQ(r.shells, 2);
  EXPECT_EQ(r.genus, (std::vector<int>{0, 0}));
}

TEST(MeshCheck, DetectsNonManifoldEdge) {
  TriangleMesh m = CubeMesh();
  // A fin on edge (0, 1).
  m.vertices.push_back({0.5f, -1, -1});
  m.faces.push_back({0, 1, 8});
  const MeshReport r = CheckMesh(m);
  EXPECT_FALSE(r.edge_manifold);
  EXPECT_EQ(r.nonmanifold_edges, 1);
  EXPECT_FALSE(r.closed);
}

TEST(MeshCheck, DetectsNonManifoldVertex) {
  // Two cubes glued at one shared vertex id (7 of the first = 0 of the second).
  TriangleMesh a = CubeMesh();
  TriangleMesh b = CubeMesh({1, 1, 1});
  TriangleMesh m = Concat(a, b);
  for (auto& f : m.faces)
    for (auto& v : f)
      if (v == 8) v = 7;
  const MeshReport r = CheckMesh(m);
  EXPECT_TRUE(r.closed);
  EXPECT_TRUE(r.edge_manifold);
  EXPECT_FALSE(r.vertex_manifold);
  EXPECT_EQ(r.nonmanifold_vertices, 1);
  EXPECT_EQ(r.unreferenced_vertices, 1);
}

TEST(MeshCheck, CountsGenusOfTorus) {
  const MeshReport r = CheckMesh(TorusMesh(24, 12, 3, 1));
  EXPECT_TRUE(r.closed);
  EXPECT_TRUE(r.manifold);
  EXPECT_TRUE(r.oriented);
  EXPECT_TRUE(r.positive_volume);
  EXPECT_EQ(r.self_intersections, 0);
  EXPECT_EQ(r.genus, std::vector<int>{1});
}

TEST(MeshCheck, CountsDegenerateFaces) {
  TriangleMesh m = CubeMesh();
  m.faces.push_back({0, 0, 1});
  m.vertices.push_back({2, 0, 0});
  m.faces.push_back({0, 1, 8});  // collinear
  EXPECT_EQ(CheckMesh(m).degenerate_faces, 2);
}

TEST(MeshCheck, SkipsFacesWithInvalidIndices) {
  TriangleMesh m = CubeMesh();
  m.faces.push_back({0, 1, 99});
  m.faces.push_back({-1, 1, 2});
  const MeshReport r = CheckMesh(m);
  EXPECT_EQ(r.invalid_faces, 2);
  EXPECT_TRUE(r.closed);
}

TEST(MeshCheck, DetectsFoldedAdjacentFaces) {
  // Two coplanar faces sharing an edge and lying on the same side of it.
  TriangleMesh m;
  m.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.5f, 0.5f, 0}};
  m.faces = {{0, 1, 2}, {1, 0, 3}};
  EXPECT_EQ(CheckMesh(m).self_intersections, 1);
}

TEST(MeshCheck, DetectsPokeThroughAtSharedVertex) {
  TriangleMesh m;
  m.vertices = {{0, 0, 0}, {2, -1, 0}, {2, 1, 0}, {1, 0, -1}, {1, 0, 1}};
  m.faces = {{0, 1, 2}, {0, 3, 4}};  // share vertex 0; the second pierces the first
  EXPECT_EQ(CheckMesh(m).self_intersections, 1);
}

TEST(MeshCheck, JsonUsesSnakeCaseKeys) {
  const std::string json = MeshReportToJson(CheckMesh(CubeMesh()));
  for (const char* key :
       {"\"closed\": true", "\"manifold\": true", "\"oriented\": true", "\"shells\": 1",
        "\"genus\": [0]", "\"self_intersections\": 0", "\"positive_volume\": true"})
    EXPECT_NE(json.find(key), std::string::npos) << key << " in " << json;
}

// Speed is measured in tests/bench, not here; this checks a million faces come out right.
TEST(MeshCheck, AMillionFaceTorusIsClosedManifoldAndClean) {
  const TriangleMesh m = TorusMesh(1000, 500, 3, 1);
  ASSERT_EQ(m.faces.size(), 1000000u);
  const MeshReport r = CheckMesh(m);
  EXPECT_TRUE(r.closed && r.manifold && r.oriented);
  EXPECT_EQ(r.self_intersections, 0);
}

}  // namespace
}  // namespace membrane
