// The big plates on a coarser grid (ShrinkOptions::coarse_plates), forced on small grids by
// their threshold: the lift leaves the membrane invariants holding, the shrink that goes on
// from it gives the shapes' topology and a closed 2-manifold mesh, and the rows say which grid
// ran each generation. Grids under the default threshold are left alone.
#include "core/engine/coarse_plates.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "core/engine/membrane_invariants.h"
#include "core/engine/plate_schedule.h"
#include "core/engine/voxelization.h"
#include "core/pipeline/reconstruction_options.h"
#include "core/synth/shape_catalog.h"
#include "tests/support/in_memory_run.h"
#include "tests/support/shrink_fixture.h"

namespace membrane::testing {
namespace {

constexpr int kPoints = 100000;

// Every grid from one voxel up; plates of 8 and more on the grid 4 times coarser (there,
// plates down to 2: chains as well as closed forms).
ShrinkOptions Forced(int threads = 1) {
  ShrinkOptions o;
  o.coarse_plates.min_voxels = 1;
  o.coarse_plates.min_plate = 8;
  o.threads = threads;
  return o;
}

Voxelization VoxelizeAtFormula(const PointCloud& cloud) {
  absl::StatusOr<Box3d> bounds = CheckedBounds(cloud.points);
  EXPECT_TRUE(bounds.ok());
  VoxelizeOptions vo;
  vo.voxel_size = EstimateVoxelSize(*bounds, static_cast<int64_t>(cloud.points.size()));
  absl::StatusOr<Voxelization> voxels = Voxelize(cloud.points, vo);
  EXPECT_TRUE(voxels.ok()) << voxels.status();
  return *std::move(voxels);
}

std::vector<int> PlatesOf(const VoxelGrid& grid) {
  std::array<int, 3> data;
  for (int d = 0; d < 3; ++d) data[d] = grid.dim(d) - 2 * VoxelGrid::kPadding;
  return PlateSizes(data, PlateSchedule::kHalving, 0);
}

TEST(CoarsePlates, CountsTheLeadingBigPlatesOnBigGridsOnly) {
  const std::vector<int> sizes = {646, 323, 162, 81, 41, 21, 11, 6, 3, 2, 1};
  ShrinkOptions o;
  EXPECT_EQ(CoarseGenerationCount(int64_t{1} << 29, sizes, o, sizes.size()), 0u);
  EXPECT_EQ(CoarseGenerationCount(int64_t{1} << 30, sizes, o, sizes.size()), 5u);
  EXPECT_EQ(CoarseGenerationCount(int64_t{1} << 30, sizes, o, 3), 3u);  // the retry's first
  o.coarse_plates.min_plate = 8;
  EXPECT_EQ(CoarseGenerationCount(int64_t{1} << 30, sizes, o, sizes.size()), 7u);
  o.schedule = PlateSchedule::kLinear;
  EXPECT_EQ(CoarseGenerationCount(int64_t{1} << 30, sizes, o, sizes.size()), 0u);
  o = ShrinkOptions{};
  o.coarse_plates.min_voxels = 0;
  EXPECT_EQ(CoarseGenerationCount(int64_t{1} << 40, sizes, o, sizes.size()), 0u);
}

TEST(CoarsePlates, OutOfRangeOptionsNameTheField) {
  ShrinkOptions o;
  o.coarse_plates.factor = 5;
  EXPECT_NE(ValidateShrinkOptions(o).message().find("coarse_plates.factor"), std::string::npos);
  o = ShrinkOptions{};
  o.coarse_plates.min_plate = 7;
  EXPECT_NE(ValidateShrinkOptions(o).message().find("coarse_plates.min_plate"),
            std::string::npos);
  o = ShrinkOptions{};
  o.coarse_plates.min_voxels = -1;
  EXPECT_NE(ValidateShrinkOptions(o).message().find("coarse_plates.min_voxels"),
            std::string::npos);
}

TEST(CoarsePlates, LiftKeepsTheMembraneInvariants) {
  for (const std::string shape : {"torus", "two-spheres", "sphere"}) {
    SCOPED_TRACE(shape);
    Voxelization voxels = VoxelizeAtFormula(SynthCloud(shape, kPoints));
    VoxelGrid& grid = voxels.grid;
    const std::vector<int> sizes = PlatesOf(grid);
    const std::vector<int> labels = GenerationLabels(static_cast<int>(sizes.size()));
    for (int threads : {1, 3}) {
      const ShrinkOptions options = Forced(threads);
      const size_t count = CoarseGenerationCount(grid.size(), sizes, options, sizes.size());
      ASSERT_GE(count, 3u) << grid.dim(0);
      VoxelGrid copy = grid;
      std::vector<GenerationStats> rows;
      int calls = 0;
      absl::StatusOr<CoarsePlatesStats> coarse = RunCoarsePlates(
          copy, options, sizes, labels, count, CancelToken::Never(),
          [&calls](const GenerationStats&) { ++calls; }, rows);
      ASSERT_TRUE(coarse.ok()) << coarse.status();
      const size_t ran = static_cast<size_t>(coarse->generations);
      ASSERT_EQ(ran, count);
      EXPECT_EQ(coarse->factor, options.coarse_plates.factor);
      EXPECT_GT(coarse->lifted_voxels, 0);
      ASSERT_EQ(rows.size(), ran);
      EXPECT_EQ(calls, static_cast<int>(ran));
      for (size_t g = 0; g < ran; ++g) {
        EXPECT_EQ(rows[g].generation, static_cast<int>(g) + 1);
        EXPECT_EQ(rows[g].plate_size, sizes[g]);
        EXPECT_EQ(rows[g].level, options.coarse_plates.factor);
      }
      InvariantOptions io;
      io.require_property3 = false;
      io.expected_hard_voxels = voxels.hard_voxels;
      EXPECT_TRUE(CheckMembraneInvariants(copy, io).ok()) << CheckMembraneInvariants(copy, io);
      // Every lifted voxel carries the label of a generation that ran on the coarse grid, and
      // the boundary is exactly the voxels left with an outside 26-neighbour.
      int64_t outside_in_data = 0, boundary_apart = 0;
      for (int z = VoxelGrid::kPadding; z < copy.dim(2) - VoxelGrid::kPadding; ++z)
        for (int y = VoxelGrid::kPadding; y < copy.dim(1) - VoxelGrid::kPadding; ++y)
          for (int x = VoxelGrid::kPadding; x < copy.dim(0) - VoxelGrid::kPadding; ++x) {
            const int64_t i = copy.Index(x, y, z);
            const VoxelState s = copy.at(i);
            if (IsBoundary(s)) {
              bool touches = false;
              for (int64_t offset : copy.neighbour_offsets())
                touches = touches || IsOutside(copy.at(i + offset));
              boundary_apart += !touches;
            }
            if (!IsOutside(s)) continue;
            ++outside_in_data;
            EXPECT_GE(GenerationLabel(s), labels[0]);
            EXPECT_LE(GenerationLabel(s), labels[ran - 1]);
          }
      EXPECT_EQ(outside_in_data, coarse->lifted_voxels);
      EXPECT_EQ(boundary_apart, 0);
    }
  }
}

TEST(CoarsePlates, ShrinkGoesOnToTheShapesTopology) {
  for (const std::string shape : {"torus", "two-spheres"}) {
    SCOPED_TRACE(shape);
    const PointCloud cloud = SynthCloud(shape, kPoints);
    const absl::StatusOr<ShrinkRun> run = ShrinkCloud(cloud, 1.0, Forced(2));
    ASSERT_TRUE(run.ok()) << run.status();
    EXPECT_TRUE(run->invariants.ok()) << run->Describe();
    const ShapeTopology expected = ExpectedTopology(shape);
    EXPECT_EQ(run->topology.shells, expected.shells) << run->Describe();
    EXPECT_EQ(run->topology.genus, expected.genus) << run->Describe();
    const std::vector<int> sizes = PlatesOf(run->voxels.grid);
    const std::vector<GenerationStats>& rows = run->result.generations;
    ASSERT_EQ(rows.size(), sizes.size());
    const CoarsePlatesStats& c = run->result.coarse_plates;
    EXPECT_EQ(c.factor, 4);
    EXPECT_GE(c.generations, 3);
    EXPECT_GT(c.lifted_voxels, 0);
    for (size_t g = 0; g < rows.size(); ++g) {
      EXPECT_EQ(rows[g].generation, static_cast<int>(g) + 1);
      EXPECT_EQ(rows[g].plate_size, sizes[g]);
      EXPECT_EQ(rows[g].level, static_cast<int>(g) < c.generations ? 4 : 1) << g;
      EXPECT_EQ(sizes[g] >= 8, static_cast<int>(g) < c.generations) << g;
    }
  }
}

TEST(CoarsePlates, MeshIsClosedAndManifoldWithTheShapesTopology) {
  for (const std::string shape : {"torus", "two-spheres"}) {
    SCOPED_TRACE(shape);
    ReconstructionOptions options;
    options.shrink = Forced();
    options.threads = 2;
    absl::StatusOr<ReconstructionReport> r = ReconstructInMemory(SynthCloud(shape, kPoints),
                                                                 options);
    ASSERT_TRUE(r.ok()) << r.status();
    EXPECT_GT(r->coarse_plates.generations, 0);
    EXPECT_EQ(r->generations.front().level, 4);
    EXPECT_EQ(r->generations.back().level, 1);
    EXPECT_TRUE(r->mesh.closed);
    EXPECT_TRUE(r->mesh.manifold);
    EXPECT_EQ(r->mesh.nonmanifold_vertices, 0);
    EXPECT_EQ(r->mesh.self_intersections, 0);
    const ShapeTopology expected = ExpectedTopology(shape);
    EXPECT_EQ(r->mesh.shells, expected.shells);
    EXPECT_EQ(r->mesh.genus, expected.genus);
  }
}

TEST(CoarsePlates, GridsUnderTheThresholdRunEveryGenerationOnTheGrid) {
  const absl::StatusOr<ShrinkRun> run = ShrinkCloud(SynthCloud("torus", kPoints), 1.0);
  ASSERT_TRUE(run.ok()) << run.status();
  EXPECT_EQ(run->result.coarse_plates.factor, 0);
  EXPECT_EQ(run->result.coarse_plates.generations, 0);
  for (const GenerationStats& row : run->result.generations) EXPECT_EQ(row.level, 1);
}

}  // namespace
}  // namespace membrane::testing
