// "-" for standard input and output: membrane in a pipe, as `cat scan.ply | membrane
// reconstruct - -o - | ...`. Whatever goes to stdout then is the file and nothing else.
#include <algorithm>
#include <fstream>
#include <string>
#include <vector>

#include "core/io/mesh_io.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "tests/support/cli_runner.h"
#include "tests/support/scratch_dir.h"

namespace membrane::testing {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;
using ::testing::Not;
using ::testing::StartsWith;

class StdStreamsTest : public ::testing::Test {
 protected:
  CliResult Run(const std::vector<std::string>& args, const std::string& stdin_path = "/dev/null") {
    return RunMembrane(args, dir_.path(), stdin_path);
  }

  // A synthetic cloud of `points` points of `shape` in the file `name`.
  std::string Synth(const std::string& shape, int points, const std::string& name) {
    const std::string path = dir_.File(name);
    EXPECT_EQ(Run({"synth", shape, "-o", path, "--points", std::to_string(points)}).exit_code, 0);
    return path;
  }

  std::string WriteText(const std::string& name, const std::string& text) {
    const std::string path = dir_.File(name);
    std::ofstream(path, std::ios::binary) << text;
    return path;
  }

  ScratchDir dir_;
};

TEST_F(StdStreamsTest, SynthToStdoutWritesTheFileBytesAndTellsStderr) {
  const std::string file = Synth("sphere", 2000, "sphere.ply");
  const CliResult piped = Run({"synth", "sphere", "-o", "-", "--points", "2000"});
  ASSERT_EQ(piped.exit_code, 0) << piped.err;
  EXPECT_EQ(piped.out, ReadWholeFile(file));
  EXPECT_THAT(piped.err, HasSubstr("wrote 2000 points of sphere to stdout"));
  // --output-format picks another format for "-".
  const CliResult xyz =
      Run({"synth", "sphere", "-o", "-", "--output-format", "xyz", "--points", "500"});
  ASSERT_EQ(xyz.exit_code, 0) << xyz.err;
  EXPECT_THAT(xyz.out, Not(StartsWith("ply")));
  EXPECT_EQ(std::count(xyz.out.begin(), xyz.out.end(), '\n'), 500);
}

TEST_F(StdStreamsTest, LocalReconstructFromStdinToStdoutGivesTheFilesMesh) {
  const std::string cloud = Synth("torus", 8000, "torus.ply");
  const CliResult files = Run({"reconstruct", cloud, "-o", dir_.File("m.ply"), "--local"});
  ASSERT_EQ(files.exit_code, 0) << files.err;
  const CliResult piped = Run({"reconstruct", "-", "-o", "-", "--local"}, cloud);
  ASSERT_EQ(piped.exit_code, 0) << piped.err;
  // stdout holds the mesh alone, byte for byte the file's; the table and summary went to stderr.
  EXPECT_EQ(piped.out, ReadWholeFile(dir_.File("m.ply")));
  EXPECT_THAT(piped.err, HasSubstr("decode: 8000 points"));
  EXPECT_THAT(piped.err, HasSubstr("plate size | soft voxels"));
  EXPECT_THAT(piped.err, HasSubstr("hard voxels"));
  // The statistics may take stdout instead; the mesh then goes to a file.
  const CliResult stats = Run({"reconstruct", "-", "-o", dir_.File("s.obj"), "--local", "-q",
                               "--stats-json", "-"},
                              cloud);
  ASSERT_EQ(stats.exit_code, 0) << stats.err;
  EXPECT_THAT(stats.out, StartsWith("{"));
  EXPECT_THAT(stats.out, HasSubstr("\"seconds\""));
  EXPECT_THAT(stats.err, HasSubstr("hard voxels"));
}

TEST_F(StdStreamsTest, StdinFormatIsToldByItsBytesOrByInputFormat) {
  const std::string ply = Synth("sphere", 3000, "sphere.ply");
  ASSERT_EQ(Run({"convert", ply, dir_.File("sphere.xyz")}).exit_code, 0);
  ASSERT_EQ(Run({"convert", ply, dir_.File("sphere.drc")}).exit_code, 0);
  for (const char* name : {"sphere.xyz", "sphere.drc", "sphere.ply"}) {
    const CliResult r =
        Run({"reconstruct", "-", "-o", dir_.File(std::string(name) + ".obj"), "--local"},
            dir_.File(name));
    EXPECT_EQ(r.exit_code, 0) << name << r.err;
  }
  // A file whose name says nothing, read as what --input-format names.
  const std::string unnamed = WriteText("scan.dat", ReadWholeFile(dir_.File("sphere.xyz")));
  EXPECT_EQ(Run({"reconstruct", unnamed, "-o", dir_.File("u.ply"), "--local",
                 "--input-format", "xyz"})
                .exit_code,
            0);
  const CliResult bad_name = Run({"reconstruct", unnamed, "-o", dir_.File("u.ply"), "--local",
                                  "--input-format", "las"});
  EXPECT_EQ(bad_name.exit_code, 3);
  EXPECT_THAT(ErrorLines(bad_name.err),
              ElementsAre(HasSubstr("--input-format 'las' is not one of: ply, obj, xyz")));
}

TEST_F(StdStreamsTest, EmptyOrUnreadableStdinIsOneLineAndExitThree) {
  const CliResult empty = Run({"reconstruct", "-", "-o", dir_.File("m.ply"), "--local"});
  EXPECT_EQ(empty.exit_code, 3);
  EXPECT_THAT(ErrorLines(empty.err), ElementsAre(HasSubstr("stdin is empty")));
  const std::string noise = WriteText("noise.bin", std::string("\x01\x02\x03 not a cloud", 16));
  const CliResult garbage = Run({"reconstruct", "-", "-o", dir_.File("m.ply"), "--local"}, noise);
  EXPECT_EQ(garbage.exit_code, 3);
  EXPECT_THAT(ErrorLines(garbage.err), ElementsAre(HasSubstr("--input-format")));
  // Named, the format's reader says what is wrong, about stdin.
  const CliResult named = Run(
      {"reconstruct", "-", "-o", dir_.File("m.ply"), "--local", "--input-format", "ply"}, noise);
  EXPECT_EQ(named.exit_code, 3);
  EXPECT_THAT(ErrorLines(named.err), ElementsAre(HasSubstr("stdin: ")));
  EXPECT_EQ(Run({"check", "-"}).exit_code, 3);
  EXPECT_EQ(Run({"convert", "-", dir_.File("c.xyz")}).exit_code, 3);
}

TEST_F(StdStreamsTest, MeshAndStatisticsCannotBothTakeStdout) {
  const std::string cloud = Synth("sphere", 2000, "sphere.ply");
  const CliResult r =
      Run({"reconstruct", cloud, "-o", "-", "--stats-json", "-", "--local"});
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_THAT(ErrorLines(r.err), ElementsAre(HasSubstr("both write to standard output")));
  EXPECT_TRUE(r.out.empty());
}

TEST_F(StdStreamsTest, ConvertAndCheckReadAndWriteStandardStreams) {
  const std::string cloud = Synth("sphere", 5000, "sphere.ply");
  ASSERT_EQ(Run({"reconstruct", cloud, "-o", dir_.File("m.ply"), "--local", "-q"}).exit_code, 0);
  // A mesh through a pipe: PLY in, Draco out, and checked from stdin.
  const CliResult drc =
      Run({"convert", "-", "-", "--output-format", "drc"}, dir_.File("m.ply"));
  ASSERT_EQ(drc.exit_code, 0) << drc.err;
  EXPECT_THAT(drc.out, StartsWith("DRACO"));
  EXPECT_THAT(drc.err, HasSubstr("to stdout"));
  const std::string drc_file = WriteText("piped.drc", drc.out);
  const CliResult check = Run({"check", "-"}, drc_file);
  EXPECT_EQ(check.exit_code, 0) << check.err;
  EXPECT_THAT(check.out, HasSubstr("genus: [0]"));
  absl::StatusOr<TriangleMesh> mesh = ReadMesh(drc_file);
  ASSERT_TRUE(mesh.ok()) << mesh.status();
  EXPECT_GT(mesh->faces.size(), 0u);
}

}  // namespace
}  // namespace membrane::testing
