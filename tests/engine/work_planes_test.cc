#include "core/engine/work_planes.h"

#include "gtest/gtest.h"

namespace membrane {
namespace {

TEST(WorkPlanes, PlanesHaveOneBitPerVoxelAndKeepTheirAddresses) {
  const VoxelGrid grid({7, 5, 6}, {0, 0, 0}, 1.0);
  WorkPlanes planes(grid);
  ASSERT_TRUE(planes.Ensure(2, CancelToken::Never()));
  FlatBitset* first = &planes.plane(0);
  first->set(3);
  ASSERT_TRUE(planes.Ensure(30, CancelToken::Never()));
  EXPECT_EQ(&planes.plane(0), first);
  EXPECT_TRUE(planes.plane(0).test(3));  // contents are left to their users
  EXPECT_EQ(planes.plane(29).bits(), grid.size());
  EXPECT_FALSE(planes.plane(29).any());
}

TEST(WorkPlanes, InteriorPlaneLeavesOutTheArrayBorder) {
  const VoxelGrid grid({4, 4, 4}, {0, 0, 0}, 1.0);
  WorkPlanes planes(grid);
  ASSERT_TRUE(planes.Ensure(1, CancelToken::Never()));
  EXPECT_EQ(planes.interior().Count(), 8);  // the 2 x 2 x 2 core
  EXPECT_TRUE(planes.interior().test(grid.Index(1, 1, 1)));
  EXPECT_FALSE(planes.interior().test(grid.Index(0, 1, 1)));
}

TEST(WorkPlanes, CancelledBeforeAllocatingReturnsFalse) {
  const VoxelGrid grid({4, 4, 4}, {0, 0, 0}, 1.0);
  WorkPlanes planes(grid);
  CancelToken cancel;
  cancel.Cancel();
  EXPECT_FALSE(planes.Ensure(3, cancel));
}

}  // namespace
}  // namespace membrane
