// Choosing formats by extension.
#include "core/io/file_format.h"

#include "gmock/gmock.h"
#include "gtest/gtest.h"

namespace membrane {
namespace {

using ::testing::HasSubstr;

TEST(FileFormat, ExtensionsAreCaseInsensitiveAndDirectoriesWithDotsDoNotCount) {
  EXPECT_EQ(*FormatFromPath("a/B.PlY", FileUse::kReadPointCloud), FileFormat::kPly);
  EXPECT_EQ(*FormatFromPath("x.TXT", FileUse::kReadPointCloud), FileFormat::kXyz);
  EXPECT_EQ(*FormatFromPath("x.Pts", FileUse::kReadPointCloud), FileFormat::kXyz);
  EXPECT_EQ(*FormatFromPath("x.pcd", FileUse::kReadPointCloud), FileFormat::kPcd);
  EXPECT_EQ(*FormatFromPath("x.DRC", FileUse::kReadMesh), FileFormat::kDrc);
  EXPECT_FALSE(FormatFromPath("dir.ply/cloud", FileUse::kReadPointCloud).ok());
}

TEST(FileFormat, EachUseSupportsItsOwnFormats) {
  EXPECT_FALSE(FormatFromPath("m.stl", FileUse::kReadPointCloud).ok());
  EXPECT_TRUE(FormatFromPath("m.stl", FileUse::kWriteMesh).ok());
  EXPECT_FALSE(FormatFromPath("c.pcd", FileUse::kWritePointCloud).ok());
  const absl::Status status = FormatFromPath("c.pcd", FileUse::kWritePointCloud).status();
  EXPECT_EQ(status.code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(status.ToString(),
              HasSubstr("point clouds can be written to .ply, .xyz, .txt, .pts, .obj, .drc"));
}

}  // namespace
}  // namespace membrane
