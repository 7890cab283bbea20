// The failure messages of the topology tests: where the handles and the merges of a DMS are.
#include <string>

#include "absl/strings/match.h"
#include "absl/strings/str_split.h"
#include "core/engine/voxel_state.h"
#include "gtest/gtest.h"
#include "tests/support/shrink_fixture.h"
#include "tests/support/topology_locator.h"

namespace membrane {
namespace {

using testing::LocateHandlesAndContacts;

TEST(TopologyLocatorTest, SphereHasNothingToReport) {
  auto run = testing::ShrinkCloud(testing::SynthCloud("sphere", 20000), 1.0);
  ASSERT_TRUE(run.ok()) << run.status();
  EXPECT_EQ(LocateHandlesAndContacts(run->voxels.grid), "");
}

TEST(TopologyLocatorTest, TorusLoopIsOneArcAroundTheHole) {
  auto run = testing::ShrinkCloud(testing::SynthCloud("torus", 20000), 1.0);
  ASSERT_TRUE(run.ok()) << run.status();
  const std::string report = LocateHandlesAndContacts(run->voxels.grid);
  EXPECT_TRUE(absl::StartsWith(report, "shell 0 (genus 1, ")) << report;
  // One loop: a single arc of the thinned solid.
  const std::vector<std::string> lines = absl::StrSplit(report, '\n', absl::SkipEmpty());
  ASSERT_EQ(lines.size(), 2u) << report;
  EXPECT_TRUE(absl::StrContains(lines[1], "voxels around (")) << report;
}

// Two blocks of hard voxels joined by a soft bar: one shell, and the contact lies on the bar.
TEST(TopologyLocatorTest, MergedBlocksMeetOnTheBar) {
  VoxelGrid grid({30, 12, 12}, {0, 0, 0}, 1.0, OutsideState(0));
  for (int z = 3; z < 9; ++z) {
    for (int y = 3; y < 9; ++y) {
      for (int x = 3; x < 27; ++x) {
        const bool block = x < 11 || x >= 19;
        const bool bar = y >= 5 && y < 7 && z >= 5 && z < 7;
        if (block) grid.set(grid.Index(x, y, z), kBoundaryHard);
        else if (bar) grid.set(grid.Index(x, y, z), kBoundarySoft);
      }
    }
  }
  const std::string report = LocateHandlesAndContacts(grid);
  EXPECT_TRUE(absl::StrContains(report, "shell 0: data components of 288 and 288 hard voxels "
                                        "meet at (1"))
      << report;
}

}  // namespace
}  // namespace membrane
