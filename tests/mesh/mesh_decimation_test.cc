// Decimation to a face budget (mesh_decimation.h): the surface's promises kept at 10% and 1%
// of its faces, on the test shapes, a genus-3 plate and a real scan; bad targets refused.
#include "core/mesh/mesh_decimation.h"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>
#include <tuple>
#include <vector>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_join.h"
#include "absl/strings/str_replace.h"
#include "core/mesh/cuberille.h"
#include "core/mesh/mesh_check.h"
#include "core/mesh/output_grid.h"
#include "core/mesh/relaxation.h"
#include "core/mesh/surface_deviation.h"
#include "core/pipeline/surface_builder.h"
#include "gtest/gtest.h"
#include "tests/mesh/mesh_builders.h"
#include "tests/mesh/test_grids.h"
#include "tests/support/shared_data.h"
#include "tests/support/shrink_fixture.h"

namespace membrane {
namespace {

// A surface and the grid its positions lie on.
struct Surface {
  TriangleMesh mesh;
  PositionGrid grid;
};

// The smooth surface of `cloud` on the grid of an 11-bit .drc file (the default output).
Surface SmoothSurfaceOf(const PointCloud& cloud) {
  Surface s;
  auto run = testing::ShrinkCloud(cloud, 1.0);
  EXPECT_TRUE(run.ok()) << run.status();
  if (!run.ok()) return s;
  VoxelGrid& grid = run->voxels.grid;
  EXPECT_TRUE(Relax(grid, CancelToken::Never()).ok());
  s.grid = OutputGrid(grid, 11);
  absl::StatusOr<BuiltSurface> built =
      BuildSurface(grid, cloud, SurfaceKind::kSmooth, s.grid, CancelToken::Never());
  EXPECT_TRUE(built.ok()) << built.status();
  if (built.ok()) s.mesh = std::move(built->mesh);
  return s;
}

double Diagonal(const TriangleMesh& mesh) {
  std::array<float, 3> lo = mesh.vertices[0], hi = mesh.vertices[0];
  for (const Point3f& p : mesh.vertices)
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], p[k]);
      hi[k] = std::max(hi[k], p[k]);
    }
  return std::hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]);
}

std::vector<int> Sorted(std::vector<int> v) {
  std::sort(v.begin(), v.end());
  return v;
}

// Decimates `surface` to `fraction` of its faces and expects every promise of the surface kept,
// the target met, and the vertices removed within `max_error` (of the bounding box's diagonal)
// of the result.
void ExpectDecimationKeepsTheSurface(const Surface& surface, double fraction, double max_error,
                                     const std::string& what) {
  ASSERT_FALSE(surface.mesh.faces.empty()) << what;
  const MeshReport before = CheckMesh(surface.mesh);
  ASSERT_TRUE(before.closed && before.manifold && before.oriented) << what;
  TriangleMesh mesh = surface.mesh;
  DecimationOptions options;
  options.target_faces =
      std::max<int64_t>(static_cast<int64_t>(fraction * mesh.faces.size()), 100);
  options.grid = surface.grid;
  absl::StatusOr<DecimationStats> stats = DecimateMesh(mesh, options);
  ASSERT_TRUE(stats.ok()) << what << ": " << stats.status();
  const MeshReport r = CheckMesh(mesh);
  const SurfaceDeviation error = MeasureDeviation(surface.mesh.vertices, mesh);
  const double diagonal = Diagonal(surface.mesh);
  const std::string description = absl::StrCat(
      what, ": ", stats->faces_before, " -> ", stats->faces_after, " faces (target ",
      options.target_faces, ", ", stats->passes, " passes, ", stats->refused, " refused), ",
      r.shells, " shells genus [", absl::StrJoin(r.genus, ","), "], closed ", r.closed,
      " manifold ", r.manifold, " oriented ", r.oriented, " self-intersections ",
      r.self_intersections, " degenerate ", r.degenerate_faces, ", error max ",
      error.max / diagonal, " mean ", error.mean / diagonal, " of the diagonal");
  std::cout << description << "\n";
  EXPECT_LE(stats->faces_after, options.target_faces) << description;
  EXPECT_EQ(stats->faces_after, r.faces) << description;
  EXPECT_TRUE(r.closed) << description;
  EXPECT_TRUE(r.manifold) << description;
  EXPECT_TRUE(r.oriented && r.positive_volume) << description;
  EXPECT_EQ(r.self_intersections, before.self_intersections) << description;
  EXPECT_EQ(r.degenerate_faces, 0) << description;
  EXPECT_EQ(r.shells, before.shells) << description;
  EXPECT_EQ(Sorted(r.genus), Sorted(before.genus)) << description;
  EXPECT_LE(error.max, max_error * diagonal) << description;
  for (const Point3f& p : mesh.vertices) {
    ASSERT_EQ(surface.grid.Snap(p), p) << description << ": a vertex off the output grid";
  }
}

TEST(MinimumFacesOfGenusTest, MatchesTheSmallestTriangulations) {
  EXPECT_EQ(MinimumFacesOfGenus(0), 4);   // tetrahedron
  EXPECT_EQ(MinimumFacesOfGenus(1), 14);  // Moebius-Kantor / Csaszar torus, 7 vertices
  EXPECT_EQ(MinimumFacesOfGenus(2), 24);  // 10 vertices (9 do not triangulate genus 2)
  EXPECT_EQ(MinimumFacesOfGenus(3), 28);  // 10 vertices
}

TEST(DecimateMeshTest, TargetBelowFourIsInvalidArgument) {
  TriangleMesh cube = testing::CubeMesh();
  const TriangleMesh original = cube;
  absl::StatusOr<DecimationStats> stats = DecimateMesh(cube, {.target_faces = 3, .grid = {}});
  ASSERT_EQ(stats.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_NE(stats.status().message().find("at least 4"), std::string::npos) << stats.status();
  EXPECT_EQ(cube.faces, original.faces);
}

TEST(DecimateMeshTest, TargetBelowTheTopologysMinimumIsInvalidArgument) {
  TriangleMesh torus = testing::Concat(testing::TorusMesh(24, 24, 1.0f, 0.4f),
                                       testing::CubeMesh({3, 3, 3}, 1));
  absl::StatusOr<DecimationStats> stats = DecimateMesh(torus, {.target_faces = 17, .grid = {}});
  ASSERT_EQ(stats.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_NE(stats.status().message().find("below the 18 faces"), std::string::npos)
      << stats.status();
}

TEST(DecimateMeshTest, OpenMeshIsFailedPreconditionAndLeftAsItWas) {
  TriangleMesh cube = testing::CubeMesh();
  cube.faces.pop_back();
  const TriangleMesh original = cube;
  absl::StatusOr<DecimationStats> stats = DecimateMesh(cube, {.target_faces = 4, .grid = {}});
  EXPECT_EQ(stats.status().code(), absl::StatusCode::kFailedPrecondition) << stats.status();
  EXPECT_EQ(cube.faces, original.faces);
  EXPECT_EQ(cube.vertices, original.vertices);
}

TEST(DecimateMeshTest, TargetAboveTheFaceCountLeavesTheMeshAsItIs) {
  TriangleMesh torus = testing::TorusMesh(16, 16, 1.0f, 0.4f);
  const TriangleMesh original = torus;
  absl::StatusOr<DecimationStats> stats = DecimateMesh(torus, {.target_faces = 100000, .grid = {}});
  ASSERT_TRUE(stats.ok()) << stats.status();
  EXPECT_EQ(stats->faces_after, stats->faces_before);
  EXPECT_EQ(torus.faces, original.faces);
}

TEST(DecimateMeshTest, AnalyticTorusGoesDownToAFewDozenFacesAsATorus) {
  const Surface torus{testing::TorusMesh(64, 64, 1.0f, 0.4f), PositionGrid{}};
  ExpectDecimationKeepsTheSurface(torus, 0.01, 0.05, "analytic torus");
}

TEST(DecimateMeshTest, CancelledRunLeavesAValidMesh) {
  TriangleMesh torus = testing::TorusMesh(128, 128, 1.0f, 0.4f);
  CancelToken cancel;
  cancel.Cancel();
  absl::StatusOr<DecimationStats> stats = DecimateMesh(torus, {.target_faces = 100, .grid = {}}, cancel);
  EXPECT_EQ(stats.status().code(), absl::StatusCode::kCancelled) << stats.status();
  const MeshReport r = CheckMesh(torus);
  EXPECT_TRUE(r.closed && r.manifold && r.oriented);
  EXPECT_EQ(r.genus, std::vector<int>{1});
}

// A plate with three holes through it (genus 3), as the blocky cuberille surface: flat parts
// where every collapse costs nothing and coplanar faces meet at right angles.
TEST(DecimateMeshTest, GenusThreePlateKeepsItsGenus) {
  VoxelGrid grid = testing::OutsideGrid(48);
  testing::MarkSolid(grid, [](int x, int y, int z) {
    if (x < 4 || x > 43 || y < 14 || y > 33 || z < 18 || z > 29) return false;
    for (int hole : {11, 24, 37})
      if (std::abs(x - hole) <= 3 && std::abs(y - 24) <= 3) return false;
    return true;
  });
  const Surface plate{Cuberille(grid), PositionGrid{}};
  ASSERT_EQ(CheckMesh(plate.mesh).genus, std::vector<int>{3});
  for (double fraction : {0.1, 0.01}) {
    ExpectDecimationKeepsTheSurface(plate, fraction, 0.1,
                                    absl::StrCat("genus-3 plate at ", fraction));
  }
}

class ShapeDecimationTest : public ::testing::TestWithParam<std::tuple<std::string, double>> {};

TEST_P(ShapeDecimationTest, KeepsClosedManifoldTopologyAndNoCrossings) {
  const auto& [shape, fraction] = GetParam();
  const Surface surface = SmoothSurfaceOf(testing::SynthCloud(shape, 40000));
  ExpectDecimationKeepsTheSurface(surface, fraction, fraction < 0.05 ? 0.02 : 0.01,
                                  absl::StrCat(shape, " at ", fraction));
}

INSTANTIATE_TEST_SUITE_P(Shapes, ShapeDecimationTest,
                         ::testing::Combine(::testing::Values("sphere", "torus", "two-spheres"),
                                            ::testing::Values(0.1, 0.01)),
                         [](const auto& info) {
                           return absl::StrReplaceAll(
                               absl::StrCat(std::get<0>(info.param), "_",
                                            std::get<1>(info.param)),
                               {{"-", "_"}, {".", "p"}});
                         });

TEST(RealCloudDecimationTest, SpotScanKeepsItsSurface) {
  MEMBRANE_REQUIRE_SHARED_DATA(data_dir);
  absl::StatusOr<PointCloud> cloud = testing::ReadSharedCloud(data_dir, "spot-scan");
  ASSERT_TRUE(cloud.ok()) << cloud.status();
  const Surface surface = SmoothSurfaceOf(*cloud);
  for (double fraction : {0.1, 0.01}) {
    ExpectDecimationKeepsTheSurface(surface, fraction, fraction < 0.05 ? 0.02 : 0.01,
                                    absl::StrCat("spot-scan at ", fraction));
  }
}

}  // namespace
}  // namespace membrane
