// The real models of ../shared/data: the expected shells and genus listed in its README, at
// the formula-(1) voxel size. Skips when ../shared/data is absent.
#include <iostream>
#include <string>
#include <tuple>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_replace.h"
#include "core/io/point_cloud_io.h"
#include "gtest/gtest.h"
#include "tests/support/shrink_fixture.h"
#include "tests/support/shared_data.h"

namespace membrane {
namespace {

struct Expected {
  const char* model;
  int shells;
  int genus;  // -1: reported, not asserted (the teapot's openings make it ambiguous)
};

constexpr Expected kModels[] = {
    {"stanford-bunny", 1, 0}, {"rocker-arm", 1, 1}, {"fandisk", 1, 0},
    {"spot", 1, 0},           {"teapot", 1, -1},
};

class RealScanTest : public ::testing::TestWithParam<std::tuple<Expected, std::string>> {};

TEST_P(RealScanTest, HasTheExpectedShellsAndGenus) {
  MEMBRANE_REQUIRE_SHARED_DATA(data_dir);
  const auto& [expected, kind] = GetParam();
  const std::string path = absl::StrCat(data_dir, "/clouds/", expected.model, "-", kind, ".ply");
  absl::StatusOr<PointCloud> cloud = ReadPointCloud(path);
  ASSERT_TRUE(cloud.ok()) << cloud.status();
  auto run = testing::ShrinkCloud(*cloud, 1.0);
  ASSERT_TRUE(run.ok()) << run.status();
  RecordProperty("topology", run->Describe());
  std::cout << expected.model << "-" << kind << ": " << run->Describe() << "\n";
  EXPECT_TRUE(run->invariants.ok()) << run->Describe();
  EXPECT_EQ(run->topology.shells, expected.shells) << run->Describe();
  if (expected.genus >= 0 && run->topology.shells == 1) {
    EXPECT_EQ(run->topology.genus[0], expected.genus) << run->Describe();
  }
}

INSTANTIATE_TEST_SUITE_P(
    SharedData, RealScanTest,
    ::testing::Combine(::testing::ValuesIn(kModels), ::testing::Values("scan", "variable")),
    [](const auto& info) {
      return absl::StrReplaceAll(
          absl::StrCat(std::get<0>(info.param).model, "_", std::get<1>(info.param)), {{"-", "_"}});
    });

}  // namespace
}  // namespace membrane
