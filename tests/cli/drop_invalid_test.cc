// --drop-invalid: organized scans mark pixels without a return with NaN. Without the flag
// the cloud is refused with the count and the flag named; with it those points are left out
// and the count reported (reconstruct: progress line, warning, statistics; convert: its line).
#include <cmath>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "tests/support/cli_runner.h"
#include "tests/support/io_test_util.h"
#include "tests/support/scratch_dir.h"

namespace membrane::testing {
namespace {

using ::testing::HasSubstr;

// A unit sphere seen from the front and from the back by two `side` x `side` depth cameras
// looking along z, as one organized PLY of 2 side^2 points: NaN where a ray misses. Sets
// *misses to how many do.
std::string OrganizedSpherePly(int side, int* misses) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  std::string body;
  *misses = 0;
  for (float sign : {1.0f, -1.0f}) {
    for (int j = 0; j < side; ++j) {
      for (int i = 0; i < side; ++i) {
        const float x = 2.4f * i / (side - 1) - 1.2f, y = 2.4f * j / (side - 1) - 1.2f;
        const float r2 = x * x + y * y;
        const bool hit = r2 < 1;
        *misses += hit ? 0 : 1;
        body += LittleEndianFloat(hit ? x : nan) + LittleEndianFloat(hit ? y : nan) +
                LittleEndianFloat(hit ? sign * std::sqrt(1 - r2) : nan);
      }
    }
  }
  return "ply\nformat binary_little_endian 1.0\nelement vertex " + std::to_string(2 * side * side) +
         "\nproperty float x\nproperty float y\nproperty float z\nend_header\n" + body;
}

class DropInvalidTest : public ::testing::Test {
 protected:
  void SetUp() override {
    ply_ = dir_.File("scan.ply");
    std::ofstream(ply_, std::ios::binary) << OrganizedSpherePly(160, &misses_);
  }
  CliResult Run(const std::vector<std::string>& args) { return RunMembrane(args, dir_.path()); }

  ScratchDir dir_;
  std::string ply_;
  int misses_ = 0;
};

TEST_F(DropInvalidTest, WithoutTheFlagTheCloudIsRefusedNamingCountAndFlag) {
  ASSERT_GT(misses_, 0);
  const std::string expected = std::to_string(misses_) +
                               " points have NaN or infinite coordinates (how organized scans "
                               "mark pixels without a return); --drop-invalid leaves them out";
  const CliResult local = Run({"reconstruct", ply_, "-o", dir_.File("m.ply"), "--local", "-q"});
  EXPECT_EQ(local.exit_code, 3);
  EXPECT_THAT(local.err, HasSubstr("scan.ply: " + expected));
  // convert reads a PLY as a mesh first; the refusal still names the flag.
  const CliResult convert = Run({"convert", ply_, dir_.File("c.xyz")});
  EXPECT_EQ(convert.exit_code, 3);
  EXPECT_THAT(convert.err, HasSubstr("scan.ply: " + expected));
}

TEST_F(DropInvalidTest, ReconstructLeavesThemOutAndSaysHowMany) {
  const std::string stats = dir_.File("stats.json");
  const CliResult r = Run({"reconstruct", ply_, "-o", dir_.File("m.ply"), "--local",
                           "--drop-invalid", "--stats-json", stats});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string note = std::to_string(misses_) +
                           " points with NaN or infinite coordinates left out by --drop-invalid";
  const int hits = 2 * 160 * 160 - misses_;
  EXPECT_THAT(r.err, HasSubstr("decode: " + std::to_string(hits) + " points (" + note + ")"));
  EXPECT_THAT(r.err, HasSubstr("warning: " + note));
  EXPECT_THAT(ReadWholeFile(stats), HasSubstr("\"warnings\": [\"" + note + "\"]"));
  EXPECT_THAT(r.out + r.err, HasSubstr("genus [0], closed, manifold"));
}

TEST_F(DropInvalidTest, ConvertLeavesThemOutOfAnOrganizedPcd) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  std::string pcd =
      "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH 3\nHEIGHT 2\n"
      "VIEWPOINT 0 0 0 1 0 0 0\nPOINTS 6\nDATA binary\n";
  for (int i = 0; i < 6; ++i) {
    const float v = i % 3 == 1 ? nan : static_cast<float>(i);
    pcd += LittleEndianFloat(v) + LittleEndianFloat(v) + LittleEndianFloat(v);
  }
  const std::string in = dir_.File("organized.pcd"), out = dir_.File("organized.xyz");
  std::ofstream(in, std::ios::binary) << pcd;
  const CliResult refused = Run({"convert", in, out});
  EXPECT_EQ(refused.exit_code, 3);
  EXPECT_THAT(refused.err, HasSubstr("organized.pcd: 2 points have NaN"));
  const CliResult r = Run({"convert", in, out, "--drop-invalid"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("wrote 4 points to " + out +
                               " (2 points with NaN or infinite coordinates left out by "
                               "--drop-invalid)"));
  EXPECT_EQ(ReadWholeFile(out), "0 0 0\n2 2 2\n3 3 3\n5 5 5\n");
}

}  // namespace
}  // namespace membrane::testing
