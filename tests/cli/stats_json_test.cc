// --stats-json writes every key of design/contracts.md with the documented type.
#include <algorithm>
#include <array>
#include <string>
#include <vector>

#include "core/engine/plate_schedule.h"
#include "core/engine/voxel_grid.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "tests/support/cli_runner.h"
#include "tests/cli/json_value.h"
#include "tests/cli/reconstruct_stats.h"
#include "tests/support/scratch_dir.h"

namespace membrane::testing {
namespace {

using Type = JsonValue::Type;

// Reconstructs a small sphere with --stats-json (and `extra_flags`) and returns the parsed
// statistics.
JsonValue SphereStats(const ScratchDir& dir, const std::vector<std::string>& extra_flags = {}) {
  const std::string cloud = dir.File("sphere.ply");
  const CliResult synth =
      RunMembrane({"synth", "sphere", "-o", cloud, "--points", "5000"}, dir.path());
  EXPECT_EQ(synth.exit_code, 0) << synth.err;
  return ReconstructStats(dir, cloud, "mesh.ply", extra_flags);
}

// Expects `object` to hold `key` of `type` (and an integer when `integer`).
void ExpectKey(const JsonValue& object, const std::string& path, const std::string& key, Type type,
               bool integer = false) {
  const JsonValue* v = object.Find(key);
  ASSERT_NE(v, nullptr) << "missing " << path << key;
  EXPECT_EQ(v->type, type) << path << key;
  if (integer) {
    EXPECT_TRUE(v->integer) << path << key << " is not an integer";
  }
}

TEST(StatsJsonTest, HasEveryDocumentedKeyWithItsType) {
  const ScratchDir dir;
  const JsonValue s = SphereStats(dir);
  ExpectKey(s, "", "points", Type::kNumber, true);
  EXPECT_EQ(s.Find("points")->number, 5000);
  ExpectKey(s, "", "voxel_size", Type::kNumber);
  ExpectKey(s, "", "grid", Type::kArray);
  ASSERT_EQ(s.Find("grid")->array.size(), 3u);
  for (const JsonValue& n : s.Find("grid")->array) EXPECT_TRUE(n.integer);
  ExpectKey(s, "", "hard_voxels", Type::kNumber, true);
  ExpectKey(s, "", "density_ratio", Type::kNumber);
  ExpectKey(s, "", "warnings", Type::kArray);
  EXPECT_TRUE(s.Find("warnings")->array.empty());  // a clean scan
  ExpectKey(s, "", "generations", Type::kArray);
  for (const JsonValue& g : s.Find("generations")->array) {
    ExpectKey(g, "generations[].", "plate_size", Type::kNumber, true);
    ExpectKey(g, "generations[].", "soft_voxels", Type::kNumber, true);
    ExpectKey(g, "generations[].", "started_contractions", Type::kNumber, true);
    ExpectKey(g, "generations[].", "backtrackings", Type::kNumber, true);
    ExpectKey(g, "generations[].", "seconds", Type::kNumber);
  }
  ExpectKey(s, "", "membrane", Type::kObject);
  for (const char* key : {"hard_voxels", "frozen_voxels", "soft_voxels", "inside_hard_voxels",
                          "inside_soft_voxels", "shells"}) {
    ExpectKey(*s.Find("membrane"), "membrane.", key, Type::kNumber, true);
  }
  ExpectKey(s, "", "mesh", Type::kObject);
  const JsonValue& mesh = *s.Find("mesh");
  ExpectKey(mesh, "mesh.", "vertices", Type::kNumber, true);
  ExpectKey(mesh, "mesh.", "faces", Type::kNumber, true);
  ExpectKey(mesh, "mesh.", "closed", Type::kBool);
  ExpectKey(mesh, "mesh.", "manifold", Type::kBool);
  ExpectKey(mesh, "mesh.", "oriented", Type::kBool);
  ExpectKey(mesh, "mesh.", "shells", Type::kNumber, true);
  ExpectKey(mesh, "mesh.", "genus", Type::kArray);
  ExpectKey(s, "", "seconds", Type::kObject);
  for (const char* key : {"decode", "voxelize", "shrink", "relax", "surface", "encode", "total"}) {
    ExpectKey(*s.Find("seconds"), "seconds.", key, Type::kNumber);
  }
  ExpectKey(s, "", "peak_rss_bytes", Type::kNumber, true);
  EXPECT_GT(s.Find("peak_rss_bytes")->number, 0);
}

// local_passes counts the passes whose snapshot was taken near the last pass's writes only: a
// generation's first pass never is, and on a 100k-point torus, whose small plates run chains
// over several passes on bricks much smaller than the grid, some later pass is.
TEST(StatsJsonTest, LocalPassesAreLaterPassesOfChainGenerations) {
  const ScratchDir dir;
  const std::string cloud = dir.File("torus.ply");
  const CliResult synth =
      RunMembrane({"synth", "torus", "-o", cloud, "--points", "100000"}, dir.path());
  ASSERT_EQ(synth.exit_code, 0) << synth.err;
  const JsonValue s = ReconstructStats(dir, cloud, "mesh.drc", {"-q"});
  ASSERT_NE(s.Find("generations"), nullptr);
  int local_passes = 0;
  for (const JsonValue& g : s.Find("generations")->array) {
    ExpectKey(g, "generations[].", "local_passes", Type::kNumber, true);
    const JsonValue* local = g.Find("local_passes");
    if (local == nullptr) continue;
    const int passes = static_cast<int>(g.Find("passes")->number);
    EXPECT_GE(local->number, 0);
    EXPECT_LE(local->number, std::max(passes - 1, 0))
        << "plate " << g.Find("plate_size")->number << ": " << passes << " passes";
    local_passes += static_cast<int>(local->number);
  }
  EXPECT_GT(local_passes, 0);
}

TEST(StatsJsonTest, OneGenerationPerPlateSizeEndingWithPlateSizeOne) {
  const ScratchDir dir;
  const JsonValue s = SphereStats(dir);
  const JsonValue* generations = s.Find("generations");
  ASSERT_NE(generations, nullptr);
  ASSERT_FALSE(generations->array.empty());
  std::vector<int> sizes;
  for (const JsonValue& g : generations->array) {
    sizes.push_back(static_cast<int>(g.Find("plate_size")->number));
  }
  EXPECT_EQ(sizes.back(), 1);
  // "grid" includes the padding; the plates are sized from the data region (halving, the
  // default, from its largest side).
  std::array<int, 3> data_dims{};
  for (int d = 0; d < 3; ++d) {
    data_dims[d] = static_cast<int>(s.Find("grid")->array[d].number) - 2 * VoxelGrid::kPadding;
  }
  EXPECT_EQ(sizes, PlateSizes(data_dims, PlateSchedule::kHalving, 0));
}

// The smooth surface's steps are parts of its stage: they add up to no more than it, and the
// fit, which every smooth surface runs, takes time. Cuberille has none of them.
TEST(StatsJsonTest, SurfaceSecondsArePartsOfTheSurfaceStage) {
  const ScratchDir dir;
  const char* const keys[] = {"prepare", "nets", "caps", "fit"};
  for (const bool smooth : {true, false}) {
    const JsonValue s = smooth ? SphereStats(dir) : SphereStats(dir, {"--surface", "cuberille"});
    ExpectKey(s, "", "surface_seconds", Type::kObject);
    const JsonValue& steps = *s.Find("surface_seconds");
    double sum = 0;
    for (const char* key : keys) {
      ExpectKey(steps, "surface_seconds.", key, Type::kNumber);
      const JsonValue* v = steps.Find(key);
      if (v == nullptr) continue;
      EXPECT_GE(v->number, 0) << key;
      if (!smooth) {
        EXPECT_EQ(v->number, 0) << key;
      }
      sum += v->number;
    }
    EXPECT_LE(sum, s.Find("seconds")->Find("surface")->number) << (smooth ? "smooth" : "cuberille");
    if (smooth) {
      EXPECT_GT(steps.Find("fit")->number, 0);
    }
  }
}

TEST(StatsJsonTest, NoRelaxLeavesRelaxationOut) {
  const ScratchDir dir;
  const JsonValue s = SphereStats(dir, {"--no-relax", "--surface", "cuberille"});
  ASSERT_NE(s.Find("relaxed"), nullptr);
  EXPECT_FALSE(s.Find("relaxed")->boolean);
  EXPECT_EQ(s.Find("seconds")->Find("relax")->number, 0);
  EXPECT_EQ(s.Find("surface")->string, "cuberille");
  EXPECT_TRUE(s.Find("mesh")->Find("closed")->boolean);
}

TEST(StatsJsonTest, ThreadsSaysHowManyRan) {
  const ScratchDir dir;
  const JsonValue s = SphereStats(dir, {"--threads", "3"});
  ASSERT_NE(s.Find("threads"), nullptr);
  EXPECT_EQ(s.Find("threads")->number, 3);
}

}  // namespace
}  // namespace membrane::testing
