// `membrane synth SHAPE -o OUTPUT`: clouds by extension, flags checked by name.
#include <filesystem>
#include <string>
#include <vector>

#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "tests/support/cli_runner.h"
#include "tests/support/scratch_dir.h"

namespace membrane::testing {
namespace {

using ::testing::AllOf;
using ::testing::ElementsAre;
using ::testing::HasSubstr;

class SynthTest : public ::testing::Test {
 protected:
  CliResult Run(const std::vector<std::string>& args) { return RunMembrane(args, dir_.path()); }
  ScratchDir dir_;
};

TEST_F(SynthTest, WritesEachPointFormat) {
  for (const char* name : {"c.ply", "c.xyz", "c.obj", "c.drc"}) {
    const std::string path = dir_.File(name);
    const CliResult r = Run({"synth", "capped-sphere", "-o", path, "--points", "500", "--holes",
                             "2", "--noise", "0.01", "--density-ratio", "5", "--seed", "7"});
    EXPECT_EQ(r.exit_code, 0) << name << ": " << r.err;
    EXPECT_TRUE(std::filesystem::exists(path)) << name;
  }
}

TEST_F(SynthTest, CubePinholesTakesVoxelAndHoleSize) {
  const CliResult r = Run({"synth", "cube-pinholes", "-o", dir_.File("cube.ply"), "--points",
                           "20000", "--voxel-size", "0.1", "--hole-size", "2"});
  EXPECT_EQ(r.exit_code, 0) << r.err;
}

TEST_F(SynthTest, UnknownShapeListsTheShapes) {
  const CliResult r = Run({"synth", "dodecahedron", "-o", dir_.File("x.ply")});
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_THAT(ErrorLines(r.err), ElementsAre(AllOf(HasSubstr("dodecahedron"), HasSubstr("torus"))));
}

TEST_F(SynthTest, OutOfRangeValueNamesTheFlag) {
  const CliResult r = Run({"synth", "sphere", "-o", dir_.File("x.ply"), "--points", "0"});
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_THAT(ErrorLines(r.err), ElementsAre(AllOf(HasSubstr("--points"), HasSubstr("[1, "))));
}

TEST_F(SynthTest, StlIsNotAPointFormat) {
  const CliResult r = Run({"synth", "sphere", "-o", dir_.File("x.stl")});
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_THAT(ErrorLines(r.err), ElementsAre(HasSubstr("x.stl")));
}

}  // namespace
}  // namespace membrane::testing
