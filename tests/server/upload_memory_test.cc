// The memory for uploads: holds grow with their buffers, never wait, are refused at once when
// they do not fit, and give their bytes back exactly once, however they are moved.
#include <utility>

#include <gtest/gtest.h>

#include "server/upload_memory.h"

namespace membrane::server {
namespace {

TEST(UploadMemory, HoldsAreRefusedWhileFullAndTakenOnceReleased) {
  UploadMemory memory(100);
  UploadMemory::Hold a;
  ASSERT_TRUE(memory.Grow(a, 40).ok());
  ASSERT_TRUE(memory.Grow(a, 20).ok());  // its buffer grew
  EXPECT_EQ(a.bytes(), 60);
  UploadMemory::Hold b;
  const absl::Status busy = memory.Grow(b, 41);
  ASSERT_EQ(busy.code(), absl::StatusCode::kResourceExhausted);
  EXPECT_NE(busy.message().find("the server is busy"), std::string::npos) << busy.message();
  EXPECT_EQ(b.bytes(), 0);  // unchanged
  EXPECT_TRUE(memory.CheckFits(41).ok());
  a.Release();
  EXPECT_EQ(memory.held(), 0);
  EXPECT_TRUE(memory.Grow(b, 41).ok());
}

TEST(UploadMemory, AnUploadOverTheWholeNeverFits) {
  UploadMemory memory(100);
  const absl::Status never = memory.CheckFits(101);
  ASSERT_EQ(never.code(), absl::StatusCode::kResourceExhausted);
  EXPECT_NE(never.message().find("over the server's memory for uploads"), std::string::npos)
      << never.message();
}

TEST(UploadMemory, AMovedHoldGivesItsBytesBackOnce) {
  UploadMemory memory(100);
  {
    UploadMemory::Hold a;
    ASSERT_TRUE(memory.Grow(a, 30).ok());
    UploadMemory::Hold moved = std::move(a);
    UploadMemory::Hold other;
    other = std::move(moved);
    EXPECT_EQ(other.bytes(), 30);
    EXPECT_EQ(memory.held(), 30);
    other.Release();
    other.Release();  // again: nothing
    EXPECT_EQ(memory.held(), 0);
    UploadMemory::Hold b;
    ASSERT_TRUE(memory.Grow(b, 50).ok());
    other = std::move(b);
    EXPECT_EQ(memory.held(), 50);
  }  // destroyed: given back
  EXPECT_EQ(memory.held(), 0);
}

TEST(UploadMemory, NoLimitTakesEverything) {
  UploadMemory memory(0);
  UploadMemory::Hold h;
  EXPECT_TRUE(memory.Grow(h, int64_t{1} << 50).ok());
  EXPECT_TRUE(memory.CheckFits(int64_t{1} << 60).ok());
}

TEST(DefaultUploadMemory, IsAnEighthOfTheTotalOrNoLimitWhenUnknown) {
  EXPECT_EQ(DefaultUploadMemory(int64_t{16} << 30), int64_t{2} << 30);
  EXPECT_EQ(DefaultUploadMemory(0), 0);
}

}  // namespace
}  // namespace membrane::server
