// --stats-json says what the shrink's passes after the generations did: the piece separation
// cuts two spheres the shrink joined, the hole opening carves the pierced disk's plug and
// keeps a thin cup wall's core closed, the gap refill fills cow-spot-belt's pockets, and at
// twice its voxel the separation cuts the hard voxels where cow and spot touch; each count
// agrees with the mesh delivered.
#include <cstdint>
#include <string>
#include <vector>

#include "absl/strings/str_format.h"
#include "core/io/point_cloud_io.h"
#include "gtest/gtest.h"
#include "tests/cli/json_value.h"
#include "tests/cli/reconstruct_stats.h"
#include "tests/support/cli_runner.h"
#include "tests/support/cup_cloud.h"
#include "tests/support/scratch_dir.h"
#include "tests/support/shared_data.h"

namespace membrane::testing {
namespace {

// Reconstructs `cloud` with --stats-json (and `extra_flags`) and returns the parsed statistics.
JsonValue StatsOf(const ScratchDir& dir, const std::string& cloud,
                  const std::vector<std::string>& extra_flags = {}) {
  std::vector<std::string> flags = {"-q"};
  flags.insert(flags.end(), extra_flags.begin(), extra_flags.end());
  return ReconstructStats(dir, cloud, "mesh.drc", flags);
}

// The integer at `object`.`key`; -1 (and a failure) when it is missing or not an integer.
int64_t Count(const JsonValue& object, const std::string& key) {
  const JsonValue* v = object.Find(key);
  EXPECT_TRUE(v != nullptr && v->integer) << key;
  return v != nullptr && v->integer ? static_cast<int64_t>(v->number) : -1;
}

// The pass's object of the statistics; an empty object (and a failure) when it is missing.
const JsonValue& Pass(const JsonValue& stats, const std::string& name) {
  static const JsonValue kNone;
  const JsonValue* v = stats.Find(name);
  EXPECT_TRUE(v != nullptr && v->type == JsonValue::Type::kObject) << name;
  return v != nullptr ? *v : kNone;
}

int64_t GenusSum(const JsonValue& stats) {
  int64_t sum = 0;
  for (const JsonValue& g : stats.Find("mesh")->Find("genus")->array) {
    sum += static_cast<int64_t>(g.number);
  }
  return sum;
}

// Every pass reports every key; on one sphere neither the separation nor the opening works.
TEST(StatsJsonPassesTest, EveryPassReportsOnASingleSphere) {
  const ScratchDir dir;
  const std::string cloud = dir.File("sphere.ply");
  ASSERT_EQ(RunMembrane({"synth", "sphere", "-o", cloud, "--points", "5000"}, dir.path()).exit_code,
            0);
  const JsonValue s = StatsOf(dir, cloud);
  const JsonValue& separation = Pass(s, "piece_separation");
  EXPECT_EQ(Count(separation, "pieces"), 1);
  EXPECT_FALSE(separation.Find("separated")->boolean);
  for (const char* key : {"cut_voxels", "hard_cut_voxels", "web_voxels", "loops_closed",
                          "far_steps_cut", "shells_before", "genus_before", "shells_after",
                          "genus_after", "cavities_after"}) {
    EXPECT_EQ(Count(separation, key), 0) << key;
  }
  EXPECT_EQ(separation.Find("cut_fraction")->number, 0);
  ASSERT_NE(separation.Find("seconds"), nullptr);
  const JsonValue& holes = Pass(s, "hole_opening");
  for (const char* key :
       {"opened", "refused", "wall_core_kept", "carved_voxels", "whole_grid_counts"}) {
    EXPECT_EQ(Count(holes, key), 0) << key;
  }
  ASSERT_NE(holes.Find("seconds"), nullptr);
  // The sparse sphere's scan leaves a voxel or two for the refill; no loop to close.
  const JsonValue& refill = Pass(s, "gap_refill");
  EXPECT_GE(Count(refill, "refilled_voxels"), 0);
  EXPECT_GE(Count(refill, "pocket_voxels"), 0);
  EXPECT_EQ(Count(refill, "loops_closed"), 0);
  // The guard's sizes on this grid: the object's tunnel plate is its data box's longest axis
  // over 24 (ShrinkOptions::tunnel_axis_ratio).
  const JsonValue& guard = Pass(s, "topology_guard");
  EXPECT_EQ(Count(guard, "tunnel_min_plate"), 5);
  const JsonValue* data_grid = s.Find("data_grid");
  ASSERT_NE(data_grid, nullptr);
  ASSERT_EQ(data_grid->array.size(), 3u);
  double longest = 0;
  for (const JsonValue& axis : data_grid->array) longest = std::max(longest, axis.number);
  ASSERT_GE(longest, 24);
  EXPECT_EQ(Count(guard, "object_tunnel_plate"), static_cast<int64_t>(longest) / 24);
  EXPECT_EQ(guard.Find("dense_rim")->number, 2);
}

// Two unit spheres 0.3 apart at a voxel of 0.092 (3.3 voxels between them): the shrink leaves
// them one shell, the separation cuts it in two.
TEST(StatsJsonPassesTest, PieceSeparationCutsTwoSpheresTheShrinkJoined) {
  const ScratchDir dir;
  const std::string cloud = dir.File("two-spheres.ply");
  ASSERT_EQ(
      RunMembrane({"synth", "two-spheres", "-o", cloud, "--points", "20000"}, dir.path()).exit_code,
      0);
  const JsonValue s = StatsOf(dir, cloud, {"--voxel-size", "0.092"});
  const JsonValue& separation = Pass(s, "piece_separation");
  EXPECT_EQ(Count(separation, "pieces"), 2);
  EXPECT_TRUE(separation.Find("separated")->boolean);
  EXPECT_GT(Count(separation, "cut_voxels"), 0);
  EXPECT_EQ(Count(separation, "shells_before"), 1);
  EXPECT_EQ(Count(separation, "shells_after"), 2);
  EXPECT_EQ(Count(separation, "genus_after"), 0);
  EXPECT_EQ(Count(separation, "cavities_after"), 0);
  EXPECT_GT(separation.Find("cut_fraction")->number, 0);
  EXPECT_LE(separation.Find("cut_fraction")->number, 0.33);
  EXPECT_EQ(Count(*s.Find("mesh"), "shells"), 2);
  EXPECT_EQ(GenusSum(s), 0);
}

// A thin-walled cup (walls 3 voxels thick): the shrink digs into the wall through its faces'
// data gaps; the plugs left in the wall's core pass the hole tests but are kept closed.
TEST(StatsJsonPassesTest, HoleOpeningKeepsACupWallsCoreClosed) {
  const ScratchDir dir;
  const std::string cloud = dir.File("cup.ply");
  ASSERT_TRUE(WritePointCloud(CupCloud(3, 100000), cloud).ok());
  const JsonValue s = StatsOf(dir, cloud);
  const JsonValue& holes = Pass(s, "hole_opening");
  EXPECT_GT(Count(holes, "wall_core_kept"), 0);
  EXPECT_EQ(Count(holes, "opened"), 0);
  EXPECT_EQ(Count(holes, "carved_voxels"), 0);
  EXPECT_EQ(Count(*s.Find("mesh"), "shells"), 1);
  EXPECT_EQ(GenusSum(s), 0);
}

// The pierced disk's hole is left plugged by the shrink at its waist and opened after it.
TEST(StatsJsonPassesTest, HoleOpeningOpensThePiercedDisk) {
  MEMBRANE_REQUIRE_SHARED_DATA(data_dir);
  const ScratchDir dir;
  const JsonValue s = StatsOf(dir, data_dir + "/clouds/pierced-disk-scan.ply");
  EXPECT_EQ(Count(Pass(s, "piece_separation"), "pieces"), 1);
  const JsonValue& holes = Pass(s, "hole_opening");
  EXPECT_EQ(Count(holes, "opened"), 1);
  EXPECT_EQ(Count(holes, "refused"), 0);
  EXPECT_GT(Count(holes, "carved_voxels"), 0);
  EXPECT_EQ(Count(*s.Find("mesh"), "shells"), 1);
  EXPECT_EQ(GenusSum(s), 1);
}

// Cow, spot and a belt joined by the shrink: the cut gives their three shells and closes the
// loops it opened; the refill fills pockets behind their scanned walls.
TEST(StatsJsonPassesTest, CowSpotBeltIsSeparatedAndRefilled) {
  MEMBRANE_REQUIRE_SHARED_DATA(data_dir);
  const ScratchDir dir;
  const JsonValue s = StatsOf(dir, data_dir + "/clouds/cow-spot-belt-scan.ply");
  const JsonValue& separation = Pass(s, "piece_separation");
  EXPECT_EQ(Count(separation, "pieces"), 3);
  EXPECT_TRUE(separation.Find("separated")->boolean);
  EXPECT_EQ(Count(separation, "shells_before"), 1);
  EXPECT_EQ(Count(separation, "shells_after"), 3);
  EXPECT_LT(Count(separation, "genus_after"), Count(separation, "genus_before"));
  EXPECT_GT(Count(separation, "cut_voxels"), 0);
  EXPECT_GT(Count(separation, "loops_closed"), 0);
  const JsonValue& refill = Pass(s, "gap_refill");
  EXPECT_GT(Count(refill, "pocket_voxels"), 0);
  EXPECT_GT(Count(refill, "refilled_voxels"), 0);
  EXPECT_EQ(Count(*s.Find("mesh"), "shells"), 3);
  EXPECT_EQ(GenusSum(s), 1);
  EXPECT_EQ(Count(separation, "hard_cut_voxels"), 0);  // its pieces' hard voxels never touch
}

// At twice the formula-(1) voxel the cow's and spot's hard voxels touch at two corners, their
// points 2.57 voxels apart there: split by their points, the touching voxels are cut (each
// beside its own data), and the belt's hole, which the cut between spot and the belt crosses,
// is opened first by the hole opening; the mesh has the three shells.
TEST(StatsJsonPassesTest, CowSpotBeltAtTwiceTheVoxelCutsTouchingHardVoxels) {
  MEMBRANE_REQUIRE_SHARED_DATA(data_dir);
  const ScratchDir dir;
  const std::string cloud = data_dir + "/clouds/cow-spot-belt-scan.ply";
  const double voxel = StatsOf(dir, cloud).Find("voxel_size")->number;
  const JsonValue s = StatsOf(dir, cloud, {"--voxel-size", absl::StrFormat("%.17g", 2 * voxel)});
  const JsonValue& separation = Pass(s, "piece_separation");
  EXPECT_EQ(Count(separation, "pieces"), 3);
  EXPECT_TRUE(separation.Find("separated")->boolean);
  EXPECT_GT(Count(separation, "hard_cut_voxels"), 0);
  EXPECT_LE(Count(separation, "hard_cut_voxels"), 4);
  EXPECT_EQ(Count(separation, "shells_after"), 3);
  EXPECT_GT(Count(Pass(s, "hole_opening"), "opened"), 0);
  EXPECT_EQ(Count(*s.Find("mesh"), "shells"), 3);
  EXPECT_EQ(GenusSum(s), 1);
}

}  // namespace
}  // namespace membrane::testing
