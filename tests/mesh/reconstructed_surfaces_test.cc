// Issue 3's promise on every output: the surfaces of reconstructed membranes (test shapes and
// the real clouds of ../shared/data) are closed, vertex-manifold, consistently oriented with
// outward normals, free of self-intersections, and have the membrane's shells and genus.
#include <algorithm>
#include <iostream>
#include <string>
#include <tuple>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_join.h"
#include "absl/strings/str_replace.h"
#include "core/engine/voxel_topology.h"
#include "core/io/draco_codec.h"
#include "core/mesh/cuberille.h"
#include "core/mesh/mesh_check.h"
#include "core/mesh/relaxation.h"
#include "core/mesh/self_intersection.h"
#include "core/mesh/smooth_surface.h"
#include "core/mesh/output_grid.h"
#include "core/pipeline/surface_builder.h"
#include "gtest/gtest.h"
#include "tests/support/shrink_fixture.h"
#include "tests/support/shared_data.h"

namespace membrane {
namespace {

// kSmoothDracoFile: the smooth surface built on the grid of an 11-bit .drc file (the default
// output), encoded and decoded: the check then judges what a user's file holds.
enum class Surface { kSmooth, kCuberille, kSmoothDracoFile };

std::string SurfaceName(Surface surface) {
  switch (surface) {
    case Surface::kSmooth: return "smooth";
    case Surface::kCuberille: return "cuberille";
    case Surface::kSmoothDracoFile: return "smooth_drc";
  }
  return "";
}

// Relaxes the final membrane, builds the surface and checks it against the membrane.
void ExpectSurfaceMatchesMembrane(const PointCloud& cloud, Surface surface, const std::string& what) {
  auto run = testing::ShrinkCloud(cloud, 1.0);
  ASSERT_TRUE(run.ok()) << run.status();
  VoxelGrid& grid = run->voxels.grid;
  ASSERT_TRUE(Relax(grid, CancelToken::Never()).ok());
  const VoxelTopology membrane = ComputeVoxelTopology(grid);
  // Relaxation never changes the topology (decision 10).
  EXPECT_EQ(membrane.shells, run->topology.shells) << what;
  EXPECT_EQ(membrane.genus, run->topology.genus) << what;
  TriangleMesh mesh;
  if (surface == Surface::kCuberille) {
    mesh = Cuberille(grid);
  } else if (surface == Surface::kSmooth) {
    absl::StatusOr<TriangleMesh> smooth = SmoothSurface(grid, cloud.points);
    ASSERT_TRUE(smooth.ok()) << smooth.status();
    mesh = *std::move(smooth);
  } else {
    const PositionGrid file_grid = OutputGrid(grid, 11);
    absl::StatusOr<BuiltSurface> smooth =
        BuildSurface(grid, cloud, SurfaceKind::kSmooth, file_grid, CancelToken::Never());
    ASSERT_TRUE(smooth.ok()) << smooth.status();
    // The pipeline's check takes the fit's crossings instead of searching: they must be what a
    // search of the whole mesh finds.
    ASSERT_TRUE(smooth->crossings.has_value()) << what;
    EXPECT_EQ(*smooth->crossings, FindIntersectingFaces(smooth->mesh)) << what;
    absl::StatusOr<DracoEncoding> file =
        EncodeDracoMesh(smooth->mesh, DracoOptionsOnGrid(file_grid, 7));
    ASSERT_TRUE(file.ok()) << file.status();
    absl::StatusOr<TriangleMesh> decoded = DecodeDracoMesh(file->bytes);
    ASSERT_TRUE(decoded.ok()) << decoded.status();
    mesh = *std::move(decoded);
  }
  const MeshReport r = CheckMesh(mesh);
  const std::string description =
      absl::StrCat(what, ": membrane ", membrane.shells, " shells genus [",
                   absl::StrJoin(membrane.genus, ","), "], mesh ", r.faces, " faces, ", r.shells,
                   " shells genus [", absl::StrJoin(r.genus, ","), "], closed ", r.closed,
                   " manifold ", r.manifold, " oriented ", r.oriented, " positive volume ",
                   r.positive_volume, " self-intersections ", r.self_intersections);
  std::cout << description << "\n";
  EXPECT_TRUE(r.closed) << description;
  EXPECT_TRUE(r.vertex_manifold && r.edge_manifold) << description;
  EXPECT_TRUE(r.oriented && r.positive_volume) << description;
  EXPECT_EQ(r.self_intersections, 0) << description;
  EXPECT_EQ(r.degenerate_faces, 0) << description;
  EXPECT_EQ(r.shells, membrane.shells) << description;
  // Shells may come in another order: compare the genus lists as multisets.
  std::vector<int> a = r.genus, b = membrane.genus;
  std::sort(a.begin(), a.end());
  std::sort(b.begin(), b.end());
  EXPECT_EQ(a, b) << description;
}

class ShapeSurfaceTest
    : public ::testing::TestWithParam<std::tuple<std::string, double, Surface>> {};

TEST_P(ShapeSurfaceTest, IsClosedManifoldOutwardWithTheMembranesTopology) {
  const auto& [shape, density, surface] = GetParam();
  ExpectSurfaceMatchesMembrane(testing::SynthCloud(shape, 40000, density), surface,
                               absl::StrCat(shape, " density ", density));
}

INSTANTIATE_TEST_SUITE_P(
    Shapes, ShapeSurfaceTest,
    ::testing::Combine(::testing::Values("sphere", "two-spheres", "torus", "capped-sphere"),
                       ::testing::Values(1.0, 30.0),
                       ::testing::Values(Surface::kSmooth, Surface::kCuberille,
                                         Surface::kSmoothDracoFile)),
    [](const auto& info) {
      return absl::StrReplaceAll(
          absl::StrCat(std::get<0>(info.param), "_density", std::get<1>(info.param), "_",
                       SurfaceName(std::get<2>(info.param))),
          {{"-", "_"}, {".", "p"}});
    });

class RealCloudSurfaceTest
    : public ::testing::TestWithParam<std::tuple<std::string, std::string, Surface>> {};

TEST_P(RealCloudSurfaceTest, IsClosedManifoldOutwardWithTheMembranesTopology) {
  MEMBRANE_REQUIRE_SHARED_DATA(data_dir);
  const auto& [model, kind, surface] = GetParam();
  absl::StatusOr<PointCloud> cloud =
      testing::ReadSharedCloud(data_dir, absl::StrCat(model, "-", kind));
  ASSERT_TRUE(cloud.ok()) << cloud.status();
  ExpectSurfaceMatchesMembrane(*cloud, surface, absl::StrCat(model, "-", kind));
}

INSTANTIATE_TEST_SUITE_P(
    SharedData, RealCloudSurfaceTest,
    ::testing::Combine(::testing::Values("stanford-bunny", "rocker-arm", "fandisk", "spot",
                                         "teapot"),
                       ::testing::Values("scan", "variable"),
                       ::testing::Values(Surface::kSmooth, Surface::kCuberille,
                                         Surface::kSmoothDracoFile)),
    [](const auto& info) {
      return absl::StrReplaceAll(
          absl::StrCat(std::get<0>(info.param), "_", std::get<1>(info.param), "_",
                       SurfaceName(std::get<2>(info.param))),
          {{"-", "_"}});
    });

}  // namespace
}  // namespace membrane
