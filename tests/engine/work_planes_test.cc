#include "core/engine/work_planes.h"

#include <array>
#include <cstdint>

#include "core/engine/interior_plane.h"
#include "core/engine/planes_ahead.h"

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

TEST(WorkPlanes, ReleasedPlanesAreMadeAgainZeroed) {
  const VoxelGrid grid({7, 5, 6}, {0, 0, 0}, 1.0);
  WorkPlanes planes(grid);
  ASSERT_TRUE(planes.Ensure(3, CancelToken::Never()));
  planes.plane(2).set(5);
  planes.Release();
  ASSERT_TRUE(planes.Ensure(3, CancelToken::Never()));
  EXPECT_EQ(planes.plane(2).bits(), grid.size());
  EXPECT_FALSE(planes.plane(2).any());
}

TEST(WorkPlanes, PlanesAreZeroedOnTheirThreads) {
  // Over two word blocks a plane (170^3 voxels), so that the zeroing is split between threads.
  const VoxelGrid grid({170, 170, 170}, {0, 0, 0}, 1.0);
  for (int threads : {1, 2, 3}) {
    WorkPlanes planes(grid, threads);
    ASSERT_TRUE(planes.Ensure(3, CancelToken::Never()));
    for (int i = 0; i < 3; ++i) {
      EXPECT_EQ(planes.plane(i).bits(), grid.size());
      EXPECT_EQ(planes.plane(i).threads(), threads);
      EXPECT_FALSE(planes.plane(i).any()) << "plane " << i << ", " << threads << " threads";
    }
  }
}

TEST(WorkPlanes, PlanesSharingTheirHaloGiveTheBitsOfPlanesOfTheirOwn) {
  // In-place runs on two threads over a grid of several halo segments, on two planes in turn
  // (their halo is one), against copies that keep their own.
  const VoxelGrid grid({170, 170, 170}, {0, 0, 0}, 1.0);
  WorkPlanes planes(grid, 2);
  ASSERT_TRUE(planes.Ensure(2, CancelToken::Never()));
  FlatBitset& a = planes.plane(0);
  FlatBitset& b = planes.plane(1);
  for (int64_t i = 0; i < grid.size(); i += 3) a.set(i);
  for (int64_t i = 0; i < grid.size(); i += 1000) b.set(i);
  FlatBitset own_a = a, own_b = b;  // copies: their own halos
  own_a.set_threads(2);
  own_b.set_threads(2);
  for (const int64_t stride : {int64_t{1}, int64_t{170}, int64_t{170} * 170}) {
    a.DilateRun(4, stride);
    own_a.DilateRun(4, stride);
    b.DilateRun(9, stride);
    own_b.DilateRun(9, stride);
  }
  for (int64_t i = 0; i < grid.size(); ++i) {
    ASSERT_EQ(a.test(i), own_a.test(i)) << i;
    ASSERT_EQ(b.test(i), own_b.test(i)) << i;
  }
}

TEST(ClearArrayBorder, LeavesTheBitsOfInteriorPlane) {
  // Odd sizes, so that rows and slabs straddle words; every bit set before.
  for (const std::array<int, 3> dims :
       {std::array<int, 3>{4, 4, 4}, {67, 3, 5}, {3, 70, 4}, {130, 9, 7}, {1, 5, 5}}) {
    const int64_t nv = static_cast<int64_t>(dims[0]) * dims[1] * dims[2];
    FlatBitset plane(nv);
    for (int64_t i = 0; i < nv; ++i) plane.set(i);
    ClearArrayBorder(dims, plane);
    const FlatBitset interior = InteriorPlane(dims);
    for (int64_t i = 0; i < nv; ++i) ASSERT_EQ(plane.test(i), interior.test(i)) << i;
  }
  const FlatBitset core = InteriorPlane({4, 4, 4});
  EXPECT_EQ(core.Count(), 8);  // the 2 x 2 x 2 core
}

TEST(WorkPlanes, CancelledBeforeAllocatingReturnsFalse) {
  const VoxelGrid grid({4, 4, 4}, {0, 0, 0}, 1.0);
  WorkPlanes planes(grid);
  CancelToken cancel;
  cancel.Cancel();
  EXPECT_FALSE(planes.Ensure(3, cancel));
}

TEST(PlanesAhead, MakesThePlanesZeroedOnAThreadOfTheirOwn) {
  const VoxelGrid grid({170, 170, 170}, {0, 0, 0}, 1.0);
  WorkPlanes planes(grid, 2);
  {
    PlanesAhead ahead(planes, WorkPlanes::kArenaPlanes, CancelToken::Never());
    ahead.Wait();
    for (int i = 0; i < WorkPlanes::kArenaPlanes; ++i) {
      EXPECT_EQ(planes.plane(i).bits(), grid.size());
      EXPECT_EQ(planes.plane(i).threads(), 2);
      EXPECT_FALSE(planes.plane(i).any()) << "plane " << i;
    }
    planes.plane(0).set(7);
  }  // the destructor after Wait joins nothing
  // The planes are the caller's: kept as they were, none made twice.
  ASSERT_TRUE(planes.Ensure(WorkPlanes::kArenaPlanes, CancelToken::Never()));
  EXPECT_TRUE(planes.plane(0).test(7));
}

TEST(PlanesAhead, StoppedByTheTokenLeavesTheRestToEnsure) {
  const VoxelGrid grid({9, 8, 7}, {0, 0, 0}, 1.0);
  WorkPlanes planes(grid);
  CancelToken cancel;
  cancel.Cancel();
  PlanesAhead(planes, 3, cancel).Wait();
  ASSERT_TRUE(planes.Ensure(3, CancelToken::Never()));
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(planes.plane(i).bits(), grid.size());
    EXPECT_FALSE(planes.plane(i).any()) << "plane " << i;
  }
}

}  // namespace
}  // namespace membrane
