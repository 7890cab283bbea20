// Every failure prints exactly one "membrane: ..." line and exits with the status of
// design/contracts.md: 2 usage, 3 invalid input, 4 unavailable or timed out.
#include <filesystem>
#include <fstream>
#include <string>

#include "absl/strings/escaping.h"
#include "gmock/gmock.h"
#include "core/io/point_cloud_io.h"
#include "gtest/gtest.h"
#include "tests/support/cli_runner.h"
#include "tests/support/survey_cloud.h"
#include "tests/support/scratch_dir.h"
#include "tests/support/uniform_noise.h"

namespace membrane::testing {
namespace {

using ::testing::AllOf;
using ::testing::ElementsAre;
using ::testing::HasSubstr;
using ::testing::Not;
using ::testing::SizeIs;

class ErrorsTest : public ::testing::Test {
 protected:
  CliResult Run(const std::vector<std::string>& args) { return RunMembrane(args, dir_.path()); }

  // A small valid cloud, for the tests whose error is in the flags rather than the input.
  std::string SphereCloud(int points = 2000) {
    const std::string path = dir_.File("sphere.ply");
    const CliResult r = Run({"synth", "sphere", "-o", path, "--points", std::to_string(points)});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return path;
  }

  ScratchDir dir_;
};

TEST_F(ErrorsTest, UnknownSubcommandIsAUsageError) {
  const CliResult r = Run({"frobnicate", "x.ply"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(ErrorLines(r.err), ElementsAre(HasSubstr("frobnicate")));
}

TEST_F(ErrorsTest, UnknownFlagIsAUsageError) {
  const CliResult r = Run({"check", "a.ply", "--frobnicate"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(ErrorLines(r.err), ElementsAre(HasSubstr("--frobnicate")));
}

TEST_F(ErrorsTest, HelpExitsZero) {
  const CliResult r = Run({"reconstruct", "--help"});
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_THAT(r.out, HasSubstr("--initial-plate"));
}

TEST_F(ErrorsTest, VersionNamesTheReleaseAndTheBuild) {
  const CliResult r = Run({"--version"});
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_EQ(r.out, std::string("membrane ") + MEMBRANE_VERSION + " (" + MEMBRANE_BUILD_TYPE +
                       " build)\n");
}

TEST_F(ErrorsTest, NoCommandPrintsTheUsageAsAUsageError) {
  const CliResult r = Run({});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("reconstruct"));
  EXPECT_THAT(r.err, HasSubstr("Exit status"));
}

TEST_F(ErrorsTest, ServerPortOutOfRangeIsInvalidInputBeforeConnecting) {
  const CliResult r = Run({"jobs", "list", "--server", "127.0.0.1:99999"});
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_THAT(ErrorLines(r.err),
              ElementsAre(HasSubstr("--server '127.0.0.1:99999': port '99999' is not a number")));
}

TEST_F(ErrorsTest, OutputsThatAreDirectoriesFailBeforeAnyWork) {
  std::filesystem::create_directory(dir_.File("dir.ply"));
  std::filesystem::create_directory(dir_.File("stats"));
  const std::string cloud = SphereCloud();
  const CliResult mesh_dir = Run({"reconstruct", cloud, "-o", dir_.File("dir.ply"), "--local"});
  EXPECT_EQ(mesh_dir.exit_code, 3);
  EXPECT_THAT(ErrorLines(mesh_dir.err), ElementsAre(HasSubstr("-o: cannot write")));
  EXPECT_THAT(mesh_dir.err, Not(HasSubstr("shrink"))) << "the run must not have started";
  const CliResult stats_dir = Run({"reconstruct", cloud, "-o", dir_.File("out.ply"), "--local",
                                   "--stats-json", dir_.File("stats")});
  EXPECT_EQ(stats_dir.exit_code, 3);
  EXPECT_THAT(ErrorLines(stats_dir.err),
              ElementsAre(HasSubstr("--stats-json: cannot write '" + dir_.File("stats") +
                                    "': it is a directory")));
  const CliResult watch_dir =
      Run({"jobs", "watch", "0123456789abcdef", "-o", dir_.File("dir.ply")});
  EXPECT_EQ(watch_dir.exit_code, 3) << "checked before connecting";
  EXPECT_THAT(ErrorLines(watch_dir.err), ElementsAre(HasSubstr("it is a directory")));
}

TEST_F(ErrorsTest, MissingInputFileIsInvalidInput) {
  const CliResult r =
      Run({"reconstruct", dir_.File("absent.ply"), "-o", dir_.File("out.ply"), "--local"});
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_THAT(r.err, ::testing::StartsWith("membrane: "));
  EXPECT_THAT(ErrorLines(r.err), ElementsAre(HasSubstr("absent.ply")));
}

TEST_F(ErrorsTest, UnknownInputExtensionIsInvalidInput) {
  const std::string path = dir_.File("cloud.abc");
  std::ofstream(path) << "0 0 0\n1 0 0\n0 1 0\n0 0 1\n";
  const CliResult r = Run({"reconstruct", path, "-o", dir_.File("out.ply"), "--local"});
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_THAT(ErrorLines(r.err), ElementsAre(HasSubstr("cloud.abc")));
}

TEST_F(ErrorsTest, UnknownOutputExtensionIsInvalidInput) {
  const CliResult r = Run({"reconstruct", SphereCloud(), "-o", dir_.File("out.xyz"), "--local"});
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_THAT(ErrorLines(r.err), ElementsAre(HasSubstr("out.xyz")));
}

// The same survey cloud as float32 (a float PLY): the file itself holds positions 0.25 m
// apart, which no move can mend, and the line says how to give it in double.
TEST_F(ErrorsTest, Float32SurveyCloudIsRefusedNamingTheSpacing) {
  absl::StatusOr<PointCloud> cloud = ReadPointCloud(SphereCloud());
  ASSERT_TRUE(cloud.ok()) << cloud.status();
  for (Point3f& p : cloud->points)
    for (int k = 0; k < 3; ++k) p[k] = static_cast<float>(p[k] + kSurveyOffset[k]);
  const std::string path = dir_.File("survey_float.ply");
  ASSERT_TRUE(WritePointCloud(*cloud, path).ok());
  const CliResult r = Run({"reconstruct", path, "-o", dir_.File("out.ply"), "--local"});
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_THAT(ErrorLines(r.err), ElementsAre(HasSubstr("float32 positions are 0.25 apart")));
  EXPECT_THAT(r.err, HasSubstr("give its coordinates in double"));
}

TEST_F(ErrorsTest, NaNCoordinatesAreInvalidInputInOneLine) {
  const std::string path = dir_.File("nan.xyz");
  std::ofstream(path) << "0 0 0\n1 0 0\nnan 1 0\n0 0 1\n1 1 1\n";
  const CliResult r = Run({"reconstruct", path, "-o", dir_.File("out.ply"), "--local"});
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_THAT(ErrorLines(r.err), ElementsAre(HasSubstr("NaN")));
  // Decoding fails first, so no progress line precedes the error.
  EXPECT_THAT(r.err, ::testing::StartsWith("membrane: "));
  EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << r.err;
}

TEST_F(ErrorsTest, NegativeInitialPlateNamesTheFlagAndItsRange) {
  const CliResult r = Run({"reconstruct", SphereCloud(), "-o", dir_.File("out.ply"), "--local",
                           "--initial-plate", "-1"});
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_THAT(ErrorLines(r.err), ElementsAre(AllOf(HasSubstr("--initial-plate"), HasSubstr("-1"),
                                                   HasSubstr("[0, 100000]"))));
}

TEST_F(ErrorsTest, NonNumericValueIsInvalidInput) {
  const CliResult r = Run({"reconstruct", SphereCloud(), "-o", dir_.File("out.ply"), "--local",
                           "--voxel-size", "small"});
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_THAT(ErrorLines(r.err), ElementsAre(HasSubstr("--voxel-size")));
}

// By default a grid is refused by its bytes, not by its voxels: the memory limit names them.
TEST_F(ErrorsTest, TinyVoxelSizeExceedsTheMemoryLimit) {
  const CliResult r = Run({"reconstruct", SphereCloud(), "-o", dir_.File("out.ply"), "--local",
                           "--voxel-size", "1e-4"});
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_THAT(ErrorLines(r.err),
              ElementsAre(AllOf(HasSubstr("voxels and the"), HasSubstr("points need about"),
                                HasSubstr("over the memory limit of"))));
  EXPECT_THAT(r.err, ::testing::EndsWith("\n"));
  EXPECT_THAT(ErrorLines(r.err).back(), HasSubstr("--voxel-size"));
}

// Without a memory limit, a grid larger than the machine is still refused before it is made.
TEST_F(ErrorsTest, TinyVoxelSizeWithoutAMemoryLimitExceedsTheMachine) {
  const CliResult r = Run({"reconstruct", SphereCloud(), "-o", dir_.File("out.ply"), "--local",
                           "--voxel-size", "1e-4", "--memory-limit", "0"});
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_THAT(ErrorLines(r.err), ElementsAre(AllOf(HasSubstr("of memory this machine has"),
                                                   HasSubstr("--voxel-size"))));
}

// A --voxel-budget given still caps the grid in voxels, naming itself.
TEST_F(ErrorsTest, GridOverAGivenVoxelBudgetNamesIt) {
  const CliResult r = Run({"reconstruct", SphereCloud(), "-o", dir_.File("out.ply"), "--local",
                           "--voxel-size", "0.01", "--voxel-budget", "1000"});
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_THAT(ErrorLines(r.err), ElementsAre(AllOf(HasSubstr("over the voxel budget of 1e+03"),
                                                   HasSubstr("--voxel-size"))));
}

// Uniform noise has no surface to find. At a voxel size given near formula (1)'s (0.017 for
// 20k points in the unit cube) its membrane is a foam whose surface takes many times the
// grid's memory. The estimate made once the membrane is known refuses it before the surface is
// built, in one line naming the limit, and nothing is written.
TEST_F(ErrorsTest, NoiseWhoseSurfaceIsOverTheMemoryLimitIsRefused) {
  const std::string path = dir_.File("noise.xyz");
  {
    std::ofstream out(path);
    for (const Point3f& p : UniformNoise(20000, 12345).points)
      out << p[0] << ' ' << p[1] << ' ' << p[2] << '\n';
  }
  const CliResult r = Run({"reconstruct", path, "-o", dir_.File("out.ply"), "--local",
                           "--quiet", "--memory-limit", "60000000", "--voxel-size", "0.017"});
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_THAT(ErrorLines(r.err),
              ElementsAre(AllOf(HasSubstr("for its surface"), HasSubstr("memory limit of 60 MB"),
                                HasSubstr("--memory-limit"), HasSubstr("foam"))));
  EXPECT_FALSE(std::ifstream(dir_.File("out.ply")).good()) << "out.ply was written";
  // By default the voxel follows the points' scatter: a few voxels hold them all.
  const CliResult coarse = Run({"reconstruct", path, "-o", dir_.File("out.ply"), "--local",
                                "--quiet", "--memory-limit", "60000000"});
  EXPECT_EQ(coarse.exit_code, 3);
  EXPECT_THAT(ErrorLines(coarse.err), ElementsAre(AllOf(HasSubstr("no surface"),
                                                        HasSubstr("do they sample a surface?"))));
  // A real cloud of the same size goes through under the same limit.
  const CliResult sphere = Run({"reconstruct", SphereCloud(20000), "-o", dir_.File("s.ply"),
                                "--local", "--quiet", "--memory-limit", "60000000"});
  EXPECT_EQ(sphere.exit_code, 0) << sphere.err;
}

TEST_F(ErrorsTest, GridOverTheMemoryLimitIsRefusedBeforeVoxelizing) {
  const CliResult r = Run({"reconstruct", SphereCloud(), "-o", dir_.File("out.ply"), "--local",
                           "--memory-limit", "100000"});
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_THAT(ErrorLines(r.err), ElementsAre(AllOf(HasSubstr("the grid of"),
                                                   HasSubstr("memory limit of 100 KB"),
                                                   HasSubstr("--voxel-size"))));
  // Refused before the first stage's line.
  EXPECT_THAT(r.err, ::testing::Not(HasSubstr("voxelize:")));
}

// The refusal names the smallest --voxel-size whose grid fits the limit, and at that size the
// grid is admitted. (Far below formula (1)'s size, as here, the membrane of a sparse cloud is
// a foam whose surface the limit may still refuse, with its own message.)
TEST_F(ErrorsTest, AGridOverTheMemoryLimitNamesTheVoxelSizeThatFits) {
  const std::string cloud = SphereCloud();
  const CliResult r = Run({"reconstruct", cloud, "-o", dir_.File("out.ply"), "--local",
                           "--quiet", "--voxel-size", "0.001", "--memory-limit", "80000000"});
  EXPECT_EQ(r.exit_code, 3);
  ASSERT_THAT(ErrorLines(r.err),
              ElementsAre(AllOf(HasSubstr("over the memory limit of 80 MB"),
                                HasSubstr("; --voxel-size "), HasSubstr(" or larger fits ("),
                                HasSubstr(" times this grid's)"))));
  const std::string line = ErrorLines(r.err).front();
  const size_t at = line.find("; --voxel-size ") + std::string("; --voxel-size ").size();
  const std::string size = line.substr(at, line.find(' ', at) - at);
  ASSERT_GT(std::stod(size), 0.001) << line;
  const CliResult fits = Run({"reconstruct", cloud, "-o", dir_.File("out.ply"), "--local",
                              "--voxel-size", size, "--memory-limit", "80000000"});
  EXPECT_THAT(fits.err, AllOf(HasSubstr("voxelize:"), Not(HasSubstr("the grid of"))));
}

TEST_F(ErrorsTest, MemoryLimitIsForLocalRunsAndNamesItsRange) {
  const CliResult remote = Run({"reconstruct", SphereCloud(), "-o", dir_.File("out.ply"),
                                "--memory-limit", "100000"});
  EXPECT_EQ(remote.exit_code, 2);
  EXPECT_THAT(ErrorLines(remote.err), ElementsAre(HasSubstr("--memory-limit requires --local")));
  const CliResult negative = Run({"reconstruct", SphereCloud(), "-o", dir_.File("out.ply"),
                                  "--local", "--memory-limit", "-2"});
  EXPECT_EQ(negative.exit_code, 3);
  EXPECT_THAT(ErrorLines(negative.err),
              ElementsAre(AllOf(HasSubstr("--memory-limit -2"), HasSubstr("0 = no limit"))));
}

TEST_F(ErrorsTest, CloudThatEnclosesNoSolidIsInvalidInputAndWritesNothing) {
  // Four corners of a tetrahedron fall in one voxel at the formula-(1) size, and the membrane
  // shrinks away: an empty mesh is no answer, in any format.
  const std::string path = dir_.File("tetrahedron.xyz");
  std::ofstream(path) << "0 0 0\n1 0 0\n0 1 0\n0 0 1\n";
  for (const char* out : {"out.ply", "out.drc"}) {
    const CliResult r = Run({"reconstruct", path, "-o", dir_.File(out), "--local", "--quiet"});
    EXPECT_EQ(r.exit_code, 3) << out;
    EXPECT_THAT(ErrorLines(r.err), ElementsAre(AllOf(HasSubstr("tetrahedron.xyz"),
                                                     HasSubstr("no surface"),
                                                     HasSubstr("4 points fill only 1 voxel"))))
        << out;
    EXPECT_FALSE(std::ifstream(dir_.File(out)).good()) << out << " was written";
  }
}

TEST_F(ErrorsTest, DracoFileThatBlowsUpTheDecoderIsInvalidInputInOneLine) {
  // 30 bytes found by fuzz_io_drc (not a seed of its corpus: in process it still blows up): one
  // point in the header, but a count inside the kd-tree data made Draco 1.5.5 allocate 2.8 GB
  // in this process. Decoded in a child under a memory limit, it is one line and exit 3.
  const std::string path = dir_.File("blowup.drc");
  std::ofstream(path, std::ios::binary) << absl::HexStringToBytes(
      "445241434f020000010100010000000101000103110001000000003903b2");
  const CliResult r = Run({"reconstruct", path, "-o", dir_.File("out.ply"), "--local"});
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_THAT(ErrorLines(r.err), ElementsAre(AllOf(HasSubstr("blowup.drc could not be decoded"),
                                                   HasSubstr("memory"))));
}

TEST_F(ErrorsTest, DracoCloudIsDecodedAndReconstructed) {
  // The same road for a good file: synth writes Draco, reconstruct decodes it in its child.
  const std::string cloud = dir_.File("sphere.drc");
  ASSERT_EQ(Run({"synth", "sphere", "-o", cloud, "--points", "3000"}).exit_code, 0);
  const CliResult r = Run({"reconstruct", cloud, "-o", dir_.File("out.ply"), "--local"});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.err + r.out, HasSubstr("decode: 3000 points"));
}

TEST_F(ErrorsTest, QuietLeavesOnlyTheErrorLine) {
  const CliResult r = Run({"reconstruct", SphereCloud(), "-o", dir_.File("out.ply"), "--local",
                           "--quiet", "--voxel-size", "1e-6"});
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_THAT(r.err, ::testing::StartsWith("membrane: "));
  EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << r.err;
}

TEST_F(ErrorsTest, WithoutLocalTheServerIsUnavailable) {
  const CliResult r = Run({"reconstruct", SphereCloud(), "-o", dir_.File("out.ply")});
  EXPECT_EQ(r.exit_code, 4);
  EXPECT_THAT(ErrorLines(r.err), ElementsAre(HasSubstr("--local")));
}

TEST_F(ErrorsTest, TimeoutOnABigCloudExitsFour) {
  const std::string cloud = SphereCloud(300000);
  const CliResult r =
      Run({"reconstruct", cloud, "-o", dir_.File("out.ply"), "--local", "--timeout", "0.01"});
  EXPECT_EQ(r.exit_code, 4);
  EXPECT_THAT(ErrorLines(r.err), ElementsAre(HasSubstr("timed out after 0.01 s")));
}

}  // namespace
}  // namespace membrane::testing
