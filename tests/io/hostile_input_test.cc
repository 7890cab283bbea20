// Hostile files: truncated, lying, non-finite, empty, misnamed, missing, garbage. Each gives
// a status that says what and where; none crashes, hangs or allocates what it was told to.
#include <filesystem>
#include <limits>
#include <string>

#include "absl/strings/str_cat.h"
#include "core/io/mesh_io.h"
#include "core/io/point_cloud_io.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "tests/support/io_test_util.h"
#include "tests/support/scratch_dir.h"

namespace membrane {
namespace {

using ::membrane::testing::LittleEndianFloat;
using ::membrane::testing::SampleCloud;
using ::membrane::testing::ScratchDir;
using ::membrane::testing::WriteTestFile;
using ::testing::AllOf;
using ::testing::HasSubstr;

constexpr absl::StatusCode kInvalid = absl::StatusCode::kInvalidArgument;

std::string BinaryPlyHeader(const std::string& vertex_count) {
  return "ply\nformat binary_little_endian 1.0\nelement vertex " + vertex_count +
         "\nproperty float x\nproperty float y\nproperty float z\nend_header\n";
}

TEST(HostileInput, TruncatedBinaryPlyNamesFileAndByteOffset) {
  const ScratchDir scratch;
  const std::string header = BinaryPlyHeader("100");
  std::string ply = header;
  for (int i = 0; i < 100; ++i)
    ply += LittleEndianFloat(i) + LittleEndianFloat(i) + LittleEndianFloat(i);
  ply.resize(header.size() + 57 * 12 + 7);  // vertex 57 is cut after 7 of its 12 bytes
  const std::string path = scratch.File("truncated.ply");
  WriteTestFile(path, ply);
  absl::StatusOr<PointCloud> cloud = ReadPointCloud(path);
  EXPECT_EQ(cloud.status().code(), kInvalid);
  EXPECT_THAT(cloud.status().ToString(),
              AllOf(HasSubstr(path), HasSubstr(absl::StrCat("at byte ", header.size() + 57 * 12)),
                    HasSubstr("vertex 57 of 100")));
}

TEST(HostileInput, TruncatedAsciiPlyNamesTheEnd) {
  const std::string ply =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nend_header\n0 0 0\n1 1 1\n2 2";
  absl::StatusOr<PointCloud> cloud = ReadPointCloudFromBuffer(ply, FileFormat::kPly, "cut.ply");
  EXPECT_EQ(cloud.status().code(), kInvalid);
  EXPECT_THAT(cloud.status().ToString(), HasSubstr("cut.ply: at byte"));
}

TEST(HostileInput, HugeVertexCountInTinyFileIsInvalidArgumentNotAnAllocation) {
  for (const std::string count : {"1000000000000", "18446744073709551615", "4294967296"}) {
    std::string ply = BinaryPlyHeader(count);
    ply += std::string(1024, '\0');
    absl::StatusOr<PointCloud> cloud = ReadPointCloudFromBuffer(ply, FileFormat::kPly, "liar.ply");
    EXPECT_EQ(cloud.status().code(), kInvalid) << count;
    EXPECT_THAT(cloud.status().ToString(), AllOf(HasSubstr("liar.ply"), HasSubstr(count)));
  }
}

TEST(HostileInput, HugeCountsInAsciiPlyFaceListsAndPcdAreRejectedBeforeAllocating) {
  const std::string ascii_ply =
      "ply\nformat ascii 1.0\nelement vertex 1000000000000\nproperty float x\nproperty float y\n"
      "property float z\nend_header\n1 2 3\n";
  EXPECT_EQ(ReadPointCloudFromBuffer(ascii_ply, FileFormat::kPly).status().code(), kInvalid);

  std::string face_list = BinaryPlyHeader("1");
  face_list.insert(face_list.find("end_header"),
                   "element face 2000000000\nproperty list uint int vertex_indices\n");
  face_list += LittleEndianFloat(0) + LittleEndianFloat(0) + LittleEndianFloat(0);
  face_list += std::string("\xff\xff\xff\xff", 4) + std::string(16, '\0');
  EXPECT_EQ(ReadMeshFromBuffer(face_list, FileFormat::kPly).status().code(), kInvalid);

  const std::string pcd =
      "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nWIDTH 4294967295\nHEIGHT 4294967295\nDATA binary\n"
      "0123456789";
  EXPECT_EQ(ReadPointCloudFromBuffer(pcd, FileFormat::kPcd).status().code(), kInvalid);
}

TEST(HostileInput, HugeListLengthInBinaryPlyIsInvalidArgument) {
  std::string ply =
      "ply\nformat binary_little_endian 1.0\nelement vertex 1\nproperty float x\n"
      "property float y\nproperty float z\nproperty list uint uchar junk\nend_header\n";
  ply += LittleEndianFloat(0) + LittleEndianFloat(0) + LittleEndianFloat(0) +
         std::string("\xff\xff\xff\x7f", 4) + "abc";
  absl::StatusOr<PointCloud> cloud = ReadPointCloudFromBuffer(ply, FileFormat::kPly, "list.ply");
  EXPECT_EQ(cloud.status().code(), kInvalid);
  EXPECT_THAT(cloud.status().ToString(), HasSubstr("list length 2147483647"));
}

TEST(HostileInput, NanAndInfinitePointsAreCountedInTheMessage) {
  const std::string xyz = "0 0 0\nnan 0 0\n1 inf 2\n-inf -inf -inf\n3 4 5\n1e39 0 0\n0 0 NaN\n";
  absl::StatusOr<PointCloud> cloud = ReadPointCloudFromBuffer(xyz, FileFormat::kXyz, "nan.xyz");
  EXPECT_EQ(cloud.status().code(), kInvalid);
  // 1e39 overflows float: it is as infinite as "inf".
  EXPECT_EQ(std::string(cloud.status().message()),
            "nan.xyz: 5 points have NaN or infinite coordinates");

  std::string ply = BinaryPlyHeader("2");
  ply += LittleEndianFloat(1) + LittleEndianFloat(2) + LittleEndianFloat(3);
  ply += LittleEndianFloat(std::numeric_limits<float>::quiet_NaN()) + LittleEndianFloat(2) +
         LittleEndianFloat(3);
  EXPECT_EQ(
      std::string(ReadPointCloudFromBuffer(ply, FileFormat::kPly, "n.ply").status().message()),
      "n.ply: 1 point has NaN or infinite coordinates");
}

TEST(HostileInput, EmptyFileIsInvalidArgumentForEveryFormat) {
  const ScratchDir scratch;
  const std::string dir = scratch.path();
  for (const char* extension : {".ply", ".obj", ".xyz", ".pts", ".pcd", ".drc"}) {
    const std::string path = dir + "/empty" + extension;
    WriteTestFile(path, "");
    absl::StatusOr<PointCloud> cloud = ReadPointCloud(path);
    EXPECT_EQ(cloud.status().code(), kInvalid) << extension;
    EXPECT_THAT(cloud.status().ToString(), HasSubstr(path + ": the file is empty"));
  }
}

TEST(HostileInput, UnknownExtensionListsTheSupportedOnes) {
  absl::StatusOr<PointCloud> cloud = ReadPointCloud("/tmp/scan.las");
  EXPECT_EQ(cloud.status().code(), kInvalid);
  EXPECT_THAT(cloud.status().ToString(),
              AllOf(HasSubstr("'.las'"), HasSubstr(".ply"), HasSubstr(".obj"), HasSubstr(".xyz"),
                    HasSubstr(".txt"), HasSubstr(".pts"), HasSubstr(".pcd"), HasSubstr(".drc")));
  EXPECT_EQ(ReadMesh("/tmp/mesh.xyz").status().code(), kInvalid);
  EXPECT_EQ(WriteMesh(membrane::testing::Octahedron(), "/tmp/noext").code(), kInvalid);
}

TEST(HostileInput, MissingFileIsNotFoundNamingThePath) {
  const ScratchDir scratch;
  const std::string path = scratch.File("does_not_exist.ply");
  absl::StatusOr<PointCloud> cloud = ReadPointCloud(path);
  EXPECT_EQ(cloud.status().code(), absl::StatusCode::kNotFound);
  EXPECT_THAT(cloud.status().ToString(), HasSubstr(path));
  EXPECT_EQ(ReadMesh(scratch.File("gone.obj")).status().code(), absl::StatusCode::kNotFound);
}

TEST(HostileInput, DirectoryNamedLikeACloudIsInvalidArgument) {
  const ScratchDir scratch;
  const std::string path = scratch.File("folder.ply");
  std::filesystem::create_directory(path);
  EXPECT_EQ(ReadPointCloud(path).status().code(), kInvalid);
}

TEST(HostileInput, GarbageBytesAsDrcAreInvalidArgument) {
  const ScratchDir scratch;
  const std::string path = scratch.File("garbage.drc");
  std::string garbage;
  for (int i = 0; i < 4096; ++i) garbage.push_back(static_cast<char>((i * 7919) >> 3));
  WriteTestFile(path, garbage);
  absl::StatusOr<PointCloud> cloud = ReadPointCloud(path);
  EXPECT_EQ(cloud.status().code(), kInvalid);
  EXPECT_THAT(cloud.status().ToString(), HasSubstr(path));
  EXPECT_EQ(ReadMesh(path).status().code(), kInvalid);
}

TEST(HostileInput, DracoPointCloudClaimingBillionsOfPointsIsRejectedBeforeDecoding) {
  absl::StatusOr<std::string> drc = WritePointCloudToBuffer(SampleCloud(10), FileFormat::kDrc, {});
  ASSERT_TRUE(drc.ok());
  drc->replace(11, 4, "\xff\xff\xff\x7f");  // the int32 point count after the 11-byte header
  absl::StatusOr<PointCloud> cloud = ReadPointCloudFromBuffer(*drc, FileFormat::kDrc, "big.drc");
  EXPECT_EQ(cloud.status().code(), kInvalid);
  EXPECT_THAT(cloud.status().ToString(),
              HasSubstr("big.drc: the Draco header declares 2147483647 points"));
}

TEST(HostileInput, EveryPrefixOfValidFilesFailsCleanlyOrReadsFewerPoints) {
  const PointCloud cloud = SampleCloud(20);
  for (FileFormat format :
       {FileFormat::kPly, FileFormat::kXyz, FileFormat::kObj, FileFormat::kDrc}) {
    absl::StatusOr<std::string> bytes = WritePointCloudToBuffer(cloud, format, {});
    ASSERT_TRUE(bytes.ok());
    for (size_t size = 0; size < bytes->size(); ++size) {
      absl::StatusOr<PointCloud> read =
          ReadPointCloudFromBuffer(absl::string_view(*bytes).substr(0, size), format);
      // Text formats cut between lines are still valid files of fewer points.
      if (read.ok()) {
        EXPECT_LE(read->points.size(), cloud.points.size());
      }
      if (format == FileFormat::kPly) {
        EXPECT_FALSE(read.ok()) << size;
      }
    }
  }
}

TEST(HostileInput, BinaryGarbageInTextFormatsIsRejected) {
  constexpr char kPrefix[] = "\x01\x02\xff\xfe\x00v 1 2\n";
  std::string garbage(kPrefix, sizeof(kPrefix) - 1);
  garbage += std::string(100, '\x80');
  for (FileFormat format :
       {FileFormat::kObj, FileFormat::kXyz, FileFormat::kPcd, FileFormat::kPly}) {
    absl::StatusOr<PointCloud> read = ReadPointCloudFromBuffer(garbage, format);
    if (format != FileFormat::kObj) {  // OBJ ignores lines it does not know
      EXPECT_EQ(read.status().code(), kInvalid);
    }
  }
}

}  // namespace
}  // namespace membrane
