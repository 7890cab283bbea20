// Invalid options are rejected with InvalidArgument naming the field and its allowed range.
#include <cmath>
#include <functional>
#include <limits>
#include <string>

#include "absl/status/status.h"
#include "core/synth/synthesize.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"

namespace membrane {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;

struct BadOption {
  std::string name;
  std::function<void(SynthOptions&)> spoil;
  std::string field;
  std::string range;
};

class InvalidOptionTest : public ::testing::TestWithParam<BadOption> {};

TEST_P(InvalidOptionTest, IsInvalidArgumentNamingTheFieldAndItsRange) {
  SynthOptions options{.shape = "sphere", .points = 1000};
  GetParam().spoil(options);
  const absl::StatusOr<PointCloud> cloud = SynthesizeShape(options);
  ASSERT_EQ(cloud.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(std::string(cloud.status().message()),
              AllOf(HasSubstr(GetParam().field), HasSubstr(GetParam().range)));
}

const double kNaN = std::numeric_limits<double>::quiet_NaN();

INSTANTIATE_TEST_SUITE_P(
    SynthOptions, InvalidOptionTest,
    ::testing::Values(
        BadOption{"ZeroPoints", [](SynthOptions& o) { o.points = 0; }, "points",
                  "[1, 50000000]"},
        BadOption{"TooManyPoints", [](SynthOptions& o) { o.points = 50'000'001; }, "points",
                  "[1, 50000000]"},
        BadOption{"DensityRatioBelowOne", [](SynthOptions& o) { o.density_ratio = 0.5; },
                  "density_ratio", "[1, 1000]"},
        BadOption{"DensityRatioAboveMax", [](SynthOptions& o) { o.density_ratio = 1001; },
                  "density_ratio", "[1, 1000]"},
        BadOption{"DensityRatioNaN", [](SynthOptions& o) { o.density_ratio = kNaN; },
                  "density_ratio", "[1, 1000]"},
        BadOption{"NegativeHoles", [](SynthOptions& o) { o.holes = -1; }, "holes", "[0, 100]"},
        BadOption{"TooManyHoles", [](SynthOptions& o) { o.holes = 101; }, "holes", "[0, 100]"},
        BadOption{"NegativeNoise", [](SynthOptions& o) { o.noise = -0.01; }, "noise",
                  "[0, 0.1]"},
        BadOption{"NoiseAboveMax", [](SynthOptions& o) { o.noise = 0.2; }, "noise", "[0, 0.1]"},
        BadOption{"NoiseNaN", [](SynthOptions& o) { o.noise = kNaN; }, "noise", "[0, 0.1]"},
        BadOption{"VoxelSizeTooSmall", [](SynthOptions& o) { o.voxel_size = 1e-4; },
                  "voxel_size", "[0.001, 1]"},
        BadOption{"HoleSizeZero", [](SynthOptions& o) { o.hole_size = 0; }, "hole_size",
                  "[1, 1000]"},
        BadOption{"UnknownShapeListsTheShapes", [](SynthOptions& o) { o.shape = "cone"; },
                  "shape 'cone'", "sphere, two-spheres, torus, capped-sphere, cube-pinholes"},
        BadOption{"CubeWithRandomHoles",
                  [](SynthOptions& o) { o.shape = "cube-pinholes", o.holes = 2; }, "holes",
                  "must be 0"},
        BadOption{"CubeWithNoise", [](SynthOptions& o) { o.shape = "cube-pinholes", o.noise = 0.01; },
                  "noise", "must be 0"},
        BadOption{"CubeWithDensityRatio",
                  [](SynthOptions& o) { o.shape = "cube-pinholes", o.density_ratio = 2; },
                  "density_ratio", "must be 1"},
        BadOption{"CubeHoleTouchingTheWallEdges",
                  [](SynthOptions& o) {
                    o.shape = "cube-pinholes", o.voxel_size = 0.5, o.hole_size = 3;
                  },
                  "hole_size", "[1, 2] for a cube of 4 voxels"},
        BadOption{"CubeWithFewerPointsThanWallVoxels",
                  [](SynthOptions& o) { o.shape = "cube-pinholes", o.voxel_size = 0.1; }, "points",
                  "[2166, 50000000]"}),
    [](const auto& info) { return info.param.name; });

TEST(ValidateSynthOptionsTest, AcceptsTheEndsOfEveryRange) {
  EXPECT_TRUE(ValidateSynthOptions({.shape = "sphere", .points = 1, .density_ratio = 1000,
                                    .holes = 100, .noise = 0.1, .voxel_size = 1,
                                    .hole_size = 1000})
                  .ok());
  EXPECT_TRUE(ValidateSynthOptions({.shape = "sphere", .points = 50'000'000, .density_ratio = 1,
                                    .holes = 0, .noise = 0, .voxel_size = 0.001})
                  .ok());
}

}  // namespace
}  // namespace membrane
