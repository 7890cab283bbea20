// `membrane render MESH -o preview.png`: the three views of a mesh as a PNG file.
#include <fstream>
#include <string>
#include <vector>

#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "core/io/file_bytes.h"
#include "core/render/mesh_views.h"
#include "core/render/png_codec.h"
#include "tests/support/cli_runner.h"
#include "tests/support/scratch_dir.h"

namespace membrane::testing {
namespace {

using ::testing::HasSubstr;

class RenderTest : public ::testing::Test {
 protected:
  CliResult Run(const std::vector<std::string>& args) { return RunMembrane(args, dir_.path()); }
  // A closed tetrahedron as OBJ.
  std::string Tetrahedron() {
    const std::string path = dir_.File("tetra.obj");
    std::ofstream(path) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
                        << "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
    return path;
  }
  ScratchDir dir_;
};

TEST_F(RenderTest, WritesThreeViewsOfTheMesh) {
  const std::string out = dir_.File("preview.png");
  const CliResult r = Run({"render", Tetrahedron(), "-o", out, "--size", "100"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const absl::StatusOr<std::string> bytes = ReadFileBytes(out);
  ASSERT_TRUE(bytes.ok()) << bytes.status();
  const absl::StatusOr<RgbImage> image = DecodePng(*bytes);
  ASSERT_TRUE(image.ok()) << image.status();
  ASSERT_EQ(image->width, 300);
  ASSERT_EQ(image->height, 100);
  const uint32_t background = MeshViewOptions().background;
  // Each view shows a right triangle with its right angle at the origin's corner of the box:
  // drawn near that corner, background at the opposite one.
  EXPECT_NE(image->At(20, 80), background);         // front: x right, z up; near x = z = 0
  EXPECT_EQ(image->At(90, 10), background);
  EXPECT_NE(image->At(100 + 20, 80), background);   // side: y right, z up
  EXPECT_EQ(image->At(100 + 90, 10), background);
  EXPECT_NE(image->At(200 + 20, 80), background);   // above: x right, y up
  EXPECT_EQ(image->At(200 + 90, 10), background);
}

TEST_F(RenderTest, OutputMustBePngAndInputAMesh) {
  CliResult r = Run({"render", Tetrahedron(), "-o", dir_.File("preview.jpg")});
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_THAT(r.err, HasSubstr("name it *.png"));
  r = Run({"render", dir_.File("missing.ply"), "-o", dir_.File("p.png")});
  EXPECT_EQ(r.exit_code, 3) << r.err;
  const std::string cloud = dir_.File("cloud.ply");
  ASSERT_EQ(Run({"synth", "sphere", "-o", cloud, "--points", "100"}).exit_code, 0);
  r = Run({"render", cloud, "-o", dir_.File("p.png")});
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_THAT(r.err, HasSubstr("has no faces"));
  r = Run({"render", Tetrahedron(), "-o", dir_.File("p.png"), "--size", "8"});
  EXPECT_EQ(r.exit_code, 3) << r.err;  // CLI11's range check: a bad value, not a bad usage
}

}  // namespace
}  // namespace membrane::testing
