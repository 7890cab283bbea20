// Georeferenced input: every reader moves coordinates from 10^4 on near 0 in double, every
// writer that holds doubles puts them back, and float32-only formats refuse such geometry.
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "core/io/coordinate_shift.h"
#include "core/io/mesh_io.h"
#include "core/io/point_cloud_io.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "tests/support/io_test_util.h"
#include "tests/support/scratch_dir.h"

namespace membrane {
namespace {

using ::membrane::testing::BigEndianFloat;
using ::membrane::testing::LittleEndianDouble;
using ::membrane::testing::LittleEndianFloat;
using ::membrane::testing::Octahedron;
using ::membrane::testing::ScratchDir;
using ::testing::ElementsAre;
using ::testing::HasSubstr;

// A UTM-like position: easting, northing and a height left in place (below 10^4).
constexpr double kEast = 512345.678, kNorth = 4123456.789, kHeight = 102.5;

// Three points a few metres apart around (kEast, kNorth, kHeight), given to 1e-4 m.
const std::vector<std::array<double, 3>>& SurveyPoints() {
  static const auto* points = new std::vector<std::array<double, 3>>{
      {kEast, kNorth, kHeight},
      {kEast + 1.2345, kNorth - 2.5001, kHeight + 0.0003},
      {kEast - 3.0007, kNorth + 0.0001, kHeight - 1.25}};
  return *points;
}

// The file coordinates a cloud stands for: position + origin, in double.
std::array<double, 3> FileCoordinates(const Point3f& p, const Origin3d& origin) {
  return {p[0] + origin[0], p[1] + origin[1], p[2] + origin[2]};
}

// Every point of `cloud` within `tolerance` of SurveyPoints(), in order.
void ExpectSurveyPoints(const PointCloud& cloud, double tolerance) {
  ASSERT_EQ(cloud.points.size(), SurveyPoints().size());
  for (size_t i = 0; i < cloud.points.size(); ++i) {
    const auto got = FileCoordinates(cloud.points[i], cloud.origin);
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(got[k], SurveyPoints()[i][k], tolerance) << "point " << i << " axis " << k;
  }
}

std::string SurveyText(absl::string_view prefix) {
  std::string text;
  for (const auto& p : SurveyPoints())
    absl::StrAppend(&text, prefix, absl::StrFormat("%.4f %.4f %.4f\n", p[0], p[1], p[2]));
  return text;
}

TEST(CoordinateShift, TheFirstFinitePointFixesAWholeUnitOriginOnLargeAxesOnly) {
  CoordinateShift shift;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const Point3f skipped = shift.Narrow(nan, 1e6, 1e6);  // not finite: fixes nothing
  EXPECT_TRUE(std::isnan(skipped[0]));
  EXPECT_EQ(shift.origin(), (Origin3d{0, 0, 0}));
  const Point3f first = shift.Narrow(kEast, -kNorth, kHeight);
  EXPECT_EQ(shift.origin(), (Origin3d{512346, -4123457, 0}));
  EXPECT_FLOAT_EQ(first[0], static_cast<float>(kEast - 512346));
  EXPECT_FLOAT_EQ(first[1], static_cast<float>(-kNorth + 4123457));
  EXPECT_FLOAT_EQ(first[2], static_cast<float>(kHeight));
  // Later points do not move the origin.
  shift.Narrow(0, 0, 5e6);
  EXPECT_EQ(shift.origin(), (Origin3d{512346, -4123457, 0}));
}

TEST(CoordinateShift, SmallAndAbsurdCoordinatesStayWhereTheyAre) {
  CoordinateShift small;
  small.Narrow(9999.5, -9999.5, 0.25);
  EXPECT_EQ(small.origin(), (Origin3d{0, 0, 0}));
  // An outlier beyond 2^40 as the first point must not set the frame of the others.
  CoordinateShift absurd;
  absurd.Narrow(1e13, 1, 1);
  EXPECT_EQ(absurd.origin(), (Origin3d{0, 0, 0}));
}

// float32 files already hold the coarse lattice: they stay where they are, so that Voxelize's
// precision check still sees it and refuses the cloud instead of a wrong genus.
TEST(CoordinateShift, BinaryFloat32PositionsAreNotMoved) {
  const Point3f far = {512345.66f, 4123456.75f, 10.5f};
  std::string ply =
      "ply\nformat binary_little_endian 1.0\nelement vertex 1\n"
      "property float x\nproperty float y\nproperty float z\nend_header\n";
  std::string ply_big =
      "ply\nformat binary_big_endian 1.0\nelement vertex 1\n"
      "property float x\nproperty float y\nproperty float z\nend_header\n";
  // A list in the vertex element sends the reader down its general path.
  std::string ply_list =
      "ply\nformat binary_little_endian 1.0\nelement vertex 1\n"
      "property float x\nproperty float y\nproperty float z\n"
      "property list uchar int tags\nend_header\n";
  std::string pcd =
      "VERSION .7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH 1\nHEIGHT 1\n"
      "POINTS 1\nDATA binary\n";
  for (float v : far) {
    ply += LittleEndianFloat(v);
    ply_big += BigEndianFloat(v);
    ply_list += LittleEndianFloat(v);
    pcd += LittleEndianFloat(v);
  }
  ply_list += std::string(1, '\0');  // an empty list
  for (const auto& [data, format] : {std::pair{ply, FileFormat::kPly},
                                     std::pair{ply_big, FileFormat::kPly},
                                     std::pair{ply_list, FileFormat::kPly},
                                     std::pair{pcd, FileFormat::kPcd}}) {
    absl::StatusOr<PointCloud> cloud = ReadPointCloudFromBuffer(data, format);
    ASSERT_TRUE(cloud.ok()) << cloud.status();
    EXPECT_EQ(cloud->origin, (Origin3d{0, 0, 0}));
    EXPECT_THAT(cloud->points, ElementsAre(far));
  }
}

TEST(CoordinateShift, EveryTextAndDoubleReaderMovesSurveyCoordinates) {
  std::string ply_binary =
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\n"
      "property double x\nproperty double y\nproperty double z\nend_header\n";
  for (const auto& p : SurveyPoints())
    for (double v : p) ply_binary += LittleEndianDouble(v);
  const std::string ply_ascii =
      "ply\nformat ascii 1.0\nelement vertex 3\n"
      "property double x\nproperty double y\nproperty double z\nend_header\n" +
      SurveyText("");
  const std::string pcd_ascii =
      "VERSION .7\nFIELDS x y z\nSIZE 8 8 8\nTYPE F F F\nCOUNT 1 1 1\nWIDTH 3\nHEIGHT 1\n"
      "POINTS 3\nDATA ascii\n" +
      SurveyText("");
  std::string pcd_binary =
      "VERSION .7\nFIELDS x y z\nSIZE 8 8 8\nTYPE F F F\nCOUNT 1 1 1\nWIDTH 3\nHEIGHT 1\n"
      "POINTS 3\nDATA binary\n";
  for (const auto& p : SurveyPoints())
    for (double v : p) pcd_binary += LittleEndianDouble(v);
  const struct {
    const char* name;
    std::string data;
    FileFormat format;
  } inputs[] = {{"ply binary", ply_binary, FileFormat::kPly},
                {"ply ascii", ply_ascii, FileFormat::kPly},
                {"xyz", SurveyText(""), FileFormat::kXyz},
                {"obj", SurveyText("v "), FileFormat::kObj},
                {"pcd ascii", pcd_ascii, FileFormat::kPcd},
                {"pcd binary", pcd_binary, FileFormat::kPcd}};
  for (const auto& input : inputs) {
    SCOPED_TRACE(input.name);
    absl::StatusOr<PointCloud> cloud = ReadPointCloudFromBuffer(input.data, input.format);
    ASSERT_TRUE(cloud.ok()) << cloud.status();
    EXPECT_EQ(cloud->origin, (Origin3d{512346, 4123457, 0}));
    // Within float32 rounding of the height (102.5, unmoved: 4e-6 apart) and of the moved
    // axes (|v| < 4: 2.4e-7 apart); as float32 at 4e6 the northing would be off by 0.25 m.
    ExpectSurveyPoints(*cloud, 1e-5);
  }
}

TEST(CoordinateShift, DoubleWritersPutTheCoordinatesBackAndFloatOnesRefuse) {
  const ScratchDir scratch;
  absl::StatusOr<PointCloud> cloud = ReadPointCloudFromBuffer(SurveyText(""), FileFormat::kXyz);
  ASSERT_TRUE(cloud.ok()) << cloud.status();
  for (const char* extension : {".ply", ".xyz", ".obj"}) {
    SCOPED_TRACE(extension);
    const std::string path = scratch.File(absl::StrCat("survey", extension));
    ASSERT_TRUE(WritePointCloud(*cloud, path).ok());
    absl::StatusOr<PointCloud> read = ReadPointCloud(path);
    ASSERT_TRUE(read.ok()) << read.status();
    ExpectSurveyPoints(*read, 1e-5);
  }
  const absl::Status drc = WritePointCloud(*cloud, scratch.File("survey.drc"));
  EXPECT_EQ(drc.code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(drc.message(), HasSubstr("(512346, 4123457, 0)"));
  EXPECT_THAT(drc.message(), HasSubstr("write .ply, .obj or .xyz"));
}

TEST(CoordinateShift, MeshesKeepTheirOriginThroughPlyAndObjAndStlAndDracoRefuse) {
  const ScratchDir scratch;
  TriangleMesh mesh = Octahedron();
  mesh.origin = {512346, 4123457, -20000};
  std::vector<std::array<double, 3>> expected;
  for (const Point3f& v : mesh.vertices) expected.push_back(FileCoordinates(v, mesh.origin));
  for (const char* extension : {".ply", ".obj"}) {
    SCOPED_TRACE(extension);
    const std::string path = scratch.File(absl::StrCat("mesh", extension));
    ASSERT_TRUE(WriteMesh(mesh, path).ok());
    absl::StatusOr<TriangleMesh> read = ReadMesh(path);
    ASSERT_TRUE(read.ok()) << read.status();
    EXPECT_NE(read->origin, (Origin3d{0, 0, 0}));
    EXPECT_EQ(read->faces, mesh.faces);
    ASSERT_EQ(read->vertices.size(), expected.size());
    for (size_t i = 0; i < expected.size(); ++i)
      for (int k = 0; k < 3; ++k)
        EXPECT_NEAR(FileCoordinates(read->vertices[i], read->origin)[k], expected[i][k], 1e-6);
  }
  for (const char* extension : {".stl", ".drc"}) {
    const absl::Status s = WriteMesh(mesh, scratch.File(absl::StrCat("mesh", extension)));
    EXPECT_EQ(s.code(), absl::StatusCode::kInvalidArgument) << extension;
    EXPECT_THAT(s.message(), HasSubstr("write .ply or .obj")) << extension;
  }
}

TEST(CoordinateShift, AsciiStlIsMovedAndItsCornersStillWeld) {
  const std::string stl =
      "solid survey\n"
      " facet normal 0 0 1\n  outer loop\n"
      "   vertex 512345.5 4123456.25 0\n   vertex 512346.5 4123456.25 0\n"
      "   vertex 512345.5 4123457.25 0\n  endloop\n endfacet\n"
      " facet normal 0 0 1\n  outer loop\n"
      "   vertex 512346.5 4123456.25 0\n   vertex 512346.5 4123457.25 0\n"
      "   vertex 512345.5 4123457.25 0\n  endloop\n endfacet\n"
      "endsolid survey\n";
  absl::StatusOr<TriangleMesh> mesh = ReadMeshFromBuffer(stl, FileFormat::kStl);
  ASSERT_TRUE(mesh.ok()) << mesh.status();
  EXPECT_EQ(mesh->origin, (Origin3d{512346, 4123456, 0}));
  EXPECT_EQ(mesh->vertices.size(), 4u);
  EXPECT_THAT(mesh->vertices[0], ElementsAre(-0.5f, 0.25f, 0.0f));
}

TEST(CoordinateShift, CadAndLabCoordinatesAreReadAndWrittenAsBefore) {
  const std::string text = "0.5 -12.25 9999\n1 2 3\n";
  absl::StatusOr<PointCloud> cloud = ReadPointCloudFromBuffer(text, FileFormat::kXyz);
  ASSERT_TRUE(cloud.ok()) << cloud.status();
  EXPECT_EQ(cloud->origin, (Origin3d{0, 0, 0}));
  EXPECT_THAT(cloud->points[0], ElementsAre(0.5f, -12.25f, 9999.0f));
  absl::StatusOr<std::string> ply = WritePointCloudToBuffer(*cloud, FileFormat::kPly);
  ASSERT_TRUE(ply.ok());
  EXPECT_THAT(*ply, HasSubstr("property float x"));
}

}  // namespace
}  // namespace membrane
