// The memory for uploads: holds never wait, are refused at once when they do not fit, and give
// their bytes back exactly once, however they are moved.
#include <utility>

#include <gtest/gtest.h>

#include "server/upload_memory.h"

namespace membrane::server {
namespace {

TEST(UploadMemory, HoldsAreRefusedWhileFullAndTakenOnceReleased) {
  UploadMemory memory(100);
  absl::StatusOr<UploadMemory::Hold> a = memory.Reserve(60);
  ASSERT_TRUE(a.ok());
  const absl::StatusOr<UploadMemory::Hold> b = memory.Reserve(41);
  ASSERT_EQ(b.status().code(), absl::StatusCode::kResourceExhausted);
  EXPECT_NE(b.status().message().find("the server is busy"), std::string::npos)
      << b.status().message();
  EXPECT_TRUE(memory.Fits(41));
  a->Release();
  EXPECT_EQ(memory.held(), 0);
  EXPECT_TRUE(memory.Reserve(41).ok());
}

TEST(UploadMemory, AnUploadOverTheWholeNeverFits) {
  UploadMemory memory(100);
  const absl::StatusOr<UploadMemory::Hold> big = memory.Reserve(101);
  ASSERT_EQ(big.status().code(), absl::StatusCode::kResourceExhausted);
  EXPECT_NE(big.status().message().find("over the server's memory for uploads"),
            std::string::npos)
      << big.status().message();
  EXPECT_FALSE(memory.Fits(101));
}

TEST(UploadMemory, AMovedHoldGivesItsBytesBackOnce) {
  UploadMemory memory(100);
  {
    absl::StatusOr<UploadMemory::Hold> a = memory.Reserve(30);
    ASSERT_TRUE(a.ok());
    UploadMemory::Hold moved = *std::move(a);
    UploadMemory::Hold other;
    other = std::move(moved);
    EXPECT_EQ(other.bytes(), 30);
    EXPECT_EQ(memory.held(), 30);
    other.Release();
    other.Release();  // again: nothing
    EXPECT_EQ(memory.held(), 0);
    absl::StatusOr<UploadMemory::Hold> b = memory.Reserve(50);
    ASSERT_TRUE(b.ok());
    other = *std::move(b);
    EXPECT_EQ(memory.held(), 50);
  }  // destroyed: given back
  EXPECT_EQ(memory.held(), 0);
}

TEST(UploadMemory, NoLimitTakesEverything) {
  UploadMemory memory(0);
  EXPECT_TRUE(memory.Reserve(int64_t{1} << 50).ok());
  EXPECT_TRUE(memory.Fits(int64_t{1} << 60));
}

TEST(DefaultUploadMemory, IsAnEighthOfTheTotalOrNoLimitWhenUnknown) {
  EXPECT_EQ(DefaultUploadMemory(int64_t{16} << 30), int64_t{2} << 30);
  EXPECT_EQ(DefaultUploadMemory(0), 0);
}

}  // namespace
}  // namespace membrane::server
