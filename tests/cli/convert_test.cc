// `membrane convert INPUT OUTPUT` between point cloud and mesh formats.
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

#include "core/io/point_cloud_io.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "tests/support/cli_runner.h"
#include "tests/support/io_test_util.h"
#include "tests/support/scratch_dir.h"

namespace membrane::testing {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;

class ConvertTest : public ::testing::Test {
 protected:
  CliResult Run(const std::vector<std::string>& args) { return RunMembrane(args, dir_.path()); }
  ScratchDir dir_;
};

TEST_F(ConvertTest, PlyToXyzToPlyKeepsEveryPoint) {
  const std::string ply = dir_.File("cloud.ply");
  ASSERT_EQ(Run({"synth", "two-spheres", "-o", ply, "--points", "1234"}).exit_code, 0);
  const std::string xyz = dir_.File("cloud.xyz");
  const CliResult to_xyz = Run({"convert", ply, xyz});
  ASSERT_EQ(to_xyz.exit_code, 0) << to_xyz.err;
  EXPECT_THAT(to_xyz.out, HasSubstr("1234 points"));
  std::ifstream in(xyz);
  int lines = 0;
  for (std::string line; std::getline(in, line);) lines += line.empty() ? 0 : 1;
  EXPECT_EQ(lines, 1234);
  const CliResult back = Run({"convert", xyz, dir_.File("back.ply")});
  ASSERT_EQ(back.exit_code, 0) << back.err;
  EXPECT_THAT(back.out, HasSubstr("1234 points"));
}

TEST_F(ConvertTest, MeshToMeshFormatKeepsFaces) {
  const std::string obj = dir_.File("tetra.obj");
  std::ofstream(obj) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
                        "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
  const std::string stl = dir_.File("tetra.stl");
  const CliResult r = Run({"convert", obj, stl});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("4 vertices and 4 faces"));
  const CliResult check = Run({"check", stl});
  EXPECT_EQ(check.exit_code, 0) << check.out << check.err;
}

// A mesh to .drc is quantized to 11 bits only where that keeps it as clean as it was: the
// float32 surface of this cloud at its formula-(1) voxel (given: by default its points, spread
// over half of the voxel they are built for, read as noise) gets 57 crossing face pairs from
// 11-bit positions.
TEST_F(ConvertTest, MeshToDracoNeverAddsCrossings) {
  const std::string cloud = dir_.File("cube.ply");
  ASSERT_EQ(Run({"synth", "cube-pinholes", "-o", cloud, "--points", "20000"}).exit_code, 0);
  const std::string ply = dir_.File("cube_mesh.ply");
  ASSERT_EQ(Run({"reconstruct", cloud, "-o", ply, "--local", "-q", "--voxel-size", "0.0343423155"})
                .exit_code,
            0);
  const std::string drc = dir_.File("cube_mesh.drc");
  const CliResult convert = Run({"convert", ply, drc});
  ASSERT_EQ(convert.exit_code, 0) << convert.err;
  EXPECT_THAT(convert.out, HasSubstr("writing float32 positions"));
  const CliResult check = Run({"check", drc});
  ASSERT_EQ(check.exit_code, 0) << check.err;
  EXPECT_THAT(check.out, HasSubstr("self-intersections: 0"));
  EXPECT_THAT(check.out, HasSubstr("degenerate faces: 0"));
}

TEST_F(ConvertTest, MeshToDracoKeepsElevenBitsWhenTheyAreClean) {
  const std::string obj = dir_.File("tetra.obj");
  {
    std::ofstream out(obj);
    out << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
  }
  const std::string drc = dir_.File("tetra.drc");
  const CliResult convert = Run({"convert", obj, drc});
  ASSERT_EQ(convert.exit_code, 0) << convert.err;
  EXPECT_THAT(convert.out, ::testing::Not(HasSubstr("float32")));
  // Range 1 on 11 bits: half a step is 1 / 2047 / 2.
  EXPECT_THAT(convert.out, HasSubstr("(11-bit positions: each coordinate within 0.000245 of"));
  const CliResult check = Run({"check", drc});
  EXPECT_THAT(check.out, HasSubstr("closed: yes"));
  EXPECT_THAT(check.out, HasSubstr("self-intersections: 0"));
}

// The bound the line reports holds: every decoded point is that close to a point of the input.
TEST_F(ConvertTest, CloudToDracoReportsAnErrorBoundThatHolds) {
  const std::string ply = dir_.File("cloud.ply");
  ASSERT_EQ(Run({"synth", "sphere", "-o", ply, "--points", "1000"}).exit_code, 0);
  const std::string drc = dir_.File("cloud.drc");
  const CliResult convert = Run({"convert", ply, drc});
  ASSERT_EQ(convert.exit_code, 0) << convert.err;
  std::smatch m;
  ASSERT_TRUE(std::regex_search(convert.out, m, std::regex("each coordinate within ([0-9.e-]+)")))
      << convert.out;
  const double bound = std::stod(m[1].str());
  EXPECT_GT(bound, 0);
  absl::StatusOr<PointCloud> input = ReadPointCloud(ply), decoded = ReadPointCloud(drc);
  ASSERT_TRUE(input.ok() && decoded.ok());
  ASSERT_EQ(decoded->points.size(), input->points.size());
  const double worst = MaxNearestChebyshev(decoded->points, input->points);
  // The line rounds to 3 digits.
  EXPECT_LE(worst, bound * 1.005);
  EXPECT_GT(worst, bound / 4);  // a bound, not a guess far above the truth
}

TEST_F(ConvertTest, MeshToPointFormatWritesItsVertices) {
  const std::string obj = dir_.File("tetra.obj");
  std::ofstream(obj) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
  const CliResult r = Run({"convert", obj, dir_.File("tetra.xyz")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("4 points"));
}

TEST_F(ConvertTest, PointCloudToStlIsInvalidInput) {
  const std::string xyz = dir_.File("cloud.xyz");
  std::ofstream(xyz) << "0 0 0\n1 0 0\n0 1 0\n0 0 1\n";
  const CliResult r = Run({"convert", xyz, dir_.File("cloud.stl")});
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_THAT(ErrorLines(r.err), ElementsAre(HasSubstr("no faces")));
}

TEST_F(ConvertTest, TextFileNamedObjIsInvalidInputNotZeroPointsWritten) {
  const std::string notes = dir_.File("notes.obj");
  std::ofstream(notes) << "these are meeting notes, not a mesh\nsecond line\n";
  const std::string out = dir_.File("notes.ply");
  const CliResult r = Run({"convert", notes, out});
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_THAT(ErrorLines(r.err), ElementsAre(HasSubstr("holds no points")));
  EXPECT_FALSE(std::ifstream(out).good()) << "nothing may be written";
}

TEST_F(ConvertTest, OutputThatIsADirectoryFailsBeforeReading) {
  const std::string ply = dir_.File("cloud.ply");
  ASSERT_EQ(Run({"synth", "sphere", "-o", ply, "--points", "500"}).exit_code, 0);
  std::filesystem::create_directory(dir_.File("taken.xyz"));
  const CliResult r = Run({"convert", ply, dir_.File("taken.xyz")});
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_THAT(ErrorLines(r.err), ElementsAre(HasSubstr("it is a directory")));
}

TEST_F(ConvertTest, OffCubeOfQuadsBecomesAClosedTriangleMesh) {
  const std::string off = dir_.File("cube.off");
  std::ofstream(off) << "OFF\n8 6 12\n"
                        "0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n"
                        "4 0 3 2 1\n4 4 5 6 7\n4 0 1 5 4\n4 1 2 6 5\n4 2 3 7 6\n4 3 0 4 7\n";
  const CliResult r = Run({"convert", off, dir_.File("cube.ply")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("8 vertices and 12 faces"));
  const CliResult check = Run({"check", dir_.File("cube.ply")});
  EXPECT_EQ(check.exit_code, 0) << check.out << check.err;
}

TEST_F(ConvertTest, OffCloudIsReconstructed) {
  const std::string xyz = dir_.File("sphere.xyz");
  ASSERT_EQ(Run({"synth", "sphere", "-o", xyz, "--points", "4000"}).exit_code, 0);
  std::ifstream in(xyz);
  std::string body, line;
  int points = 0;
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    body += line + "\n";
    ++points;
  }
  const std::string off = dir_.File("sphere.off");
  std::ofstream(off) << "OFF\n" << points << " 0 0\n" << body;
  const CliResult r = Run({"reconstruct", off, "-o", dir_.File("sphere.ply"), "--local", "-q"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("4000 points"));
}

TEST_F(ConvertTest, UnknownOutputExtensionFailsBeforeReading) {
  const CliResult r = Run({"convert", dir_.File("absent.ply"), dir_.File("out.vtk")});
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_THAT(ErrorLines(r.err), ElementsAre(HasSubstr("out.vtk")));
}

}  // namespace
}  // namespace membrane::testing
