// `membrane check MESH [--json]`: exit 0 for a closed, manifold, oriented mesh, 5 otherwise.
#include <fstream>
#include <string>
#include <vector>

#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "tests/support/cli_runner.h"
#include "tests/cli/json_value.h"
#include "tests/support/scratch_dir.h"

namespace membrane::testing {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;

class CheckTest : public ::testing::Test {
 protected:
  CliResult Run(const std::vector<std::string>& args) { return RunMembrane(args, dir_.path()); }
  // Writes an OBJ with the tetrahedron's vertices and `faces` ("f ..." lines).
  std::string Tetrahedron(const std::string& name, const std::string& faces) {
    const std::string path = dir_.File(name);
    std::ofstream(path) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n" << faces;
    return path;
  }
  ScratchDir dir_;
};

TEST_F(CheckTest, ClosedTetrahedronPassesWithJsonReport) {
  const std::string mesh = Tetrahedron("tetra.obj", "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n");
  const CliResult r = Run({"check", mesh, "--json"});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  std::optional<JsonValue> json = ParseJson(r.out);
  ASSERT_TRUE(json.has_value()) << r.out;
  for (const char* key : {"closed", "manifold", "oriented"}) {
    ASSERT_NE(json->Find(key), nullptr) << key;
    EXPECT_TRUE(json->Find(key)->boolean) << key;
  }
  ASSERT_NE(json->Find("self_intersections"), nullptr);
  EXPECT_EQ(json->Find("shells")->number, 1);
}

TEST_F(CheckTest, OpenMeshFailsWithOneLineNamingWhatFailed) {
  const std::string mesh = Tetrahedron("open.obj", "f 1 3 2\nf 1 2 4\nf 1 4 3\n");
  const CliResult r = Run({"check", mesh});
  EXPECT_EQ(r.exit_code, 5);
  EXPECT_THAT(r.out, HasSubstr("closed: no"));
  EXPECT_THAT(ErrorLines(r.err), ElementsAre(HasSubstr("not closed")));
}

TEST_F(CheckTest, FlippedFaceIsNotOriented) {
  const std::string mesh = Tetrahedron("flipped.obj", "f 1 2 3\nf 1 2 4\nf 1 4 3\nf 2 3 4\n");
  const CliResult r = Run({"check", mesh});
  EXPECT_EQ(r.exit_code, 5);
  EXPECT_THAT(ErrorLines(r.err), ElementsAre(HasSubstr("not oriented")));
}

TEST_F(CheckTest, PointCloudIsInvalidInput) {
  const std::string path = dir_.File("points.ply");
  ASSERT_EQ(Run({"synth", "sphere", "-o", path, "--points", "100"}).exit_code, 0);
  const CliResult r = Run({"check", path});
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_THAT(ErrorLines(r.err), ElementsAre(HasSubstr("no faces")));
}

TEST_F(CheckTest, GarbageFileIsInvalidInput) {
  const std::string path = dir_.File("garbage.ply");
  std::ofstream(path) << "this is not a ply file\n";
  const CliResult r = Run({"check", path});
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_THAT(ErrorLines(r.err), ElementsAre(HasSubstr("garbage.ply")));
}

TEST_F(CheckTest, DracoMeshIsDecodedInAChildWithEveryFace) {
  // A .drc mesh reaches the check through the decode helper's faces protocol: the report must
  // be that of the .ply written from the same reconstruction.
  const std::string cloud = dir_.File("torus.ply");
  ASSERT_EQ(Run({"synth", "torus", "-o", cloud, "--points", "8000"}).exit_code, 0);
  for (const char* out : {"torus.drc", "torus-out.ply"}) {
    ASSERT_EQ(Run({"reconstruct", cloud, "-o", dir_.File(out), "--local", "--quantization", "0",
                   "--quiet"})
                  .exit_code,
              0);
  }
  const CliResult drc = Run({"check", dir_.File("torus.drc"), "--json"});
  const CliResult ply = Run({"check", dir_.File("torus-out.ply"), "--json"});
  ASSERT_EQ(drc.exit_code, 0) << drc.err;
  ASSERT_EQ(ply.exit_code, 0) << ply.err;
  std::optional<JsonValue> a = ParseJson(drc.out), b = ParseJson(ply.out);
  ASSERT_TRUE(a.has_value() && b.has_value()) << drc.out << ply.out;
  for (const char* key : {"vertices", "faces", "shells", "self_intersections"}) {
    EXPECT_EQ(a->Find(key)->number, b->Find(key)->number) << key;
  }
  EXPECT_GT(a->Find("faces")->number, 1000);
}

TEST_F(CheckTest, DracoPointCloudIsInvalidInputInOneLine) {
  const std::string path = dir_.File("points.drc");
  ASSERT_EQ(Run({"synth", "sphere", "-o", path, "--points", "100"}).exit_code, 0);
  const CliResult r = Run({"check", path});
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_THAT(ErrorLines(r.err), ElementsAre(AllOf(HasSubstr("points.drc"),
                                                   HasSubstr("a point cloud, not a mesh"))));
}

}  // namespace
}  // namespace membrane::testing
