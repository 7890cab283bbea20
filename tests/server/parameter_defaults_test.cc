// Parameters a client leaves unset get the server's defaults, and 0 set explicitly means 0:
// a client written from the .proto alone gets the mesh `membrane reconstruct` would.
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "server/parameter_checks.h"
#include "tests/server/service_fixture.h"

namespace membrane::testing {
namespace {

// The statistics JSON of a finished call.
std::string StatisticsOf(const CallResult& r) {
  for (const v1::JobEvent& e : r.events) {
    if (e.has_result()) return e.result().statistics_json();
  }
  return "";
}

TEST_F(ServiceTest, UnsetQuantizationAndLevelGetTheDefaultsAndZeroMeansZero) {
  StartServer();
  const std::string cloud = DracoCloud("sphere", 20000);
  const CallResult unset = Reconstruct(cloud, v1::Parameters());
  ASSERT_TRUE(unset.status.ok()) << unset.status.error_message();
  EXPECT_NE(StatisticsOf(unset).find("\"requested_bits\": 11"), std::string::npos)
      << StatisticsOf(unset);

  v1::Parameters defaults;
  defaults.set_quantization(11);
  defaults.set_compression_level(7);
  const CallResult given = Reconstruct(cloud, defaults);
  ASSERT_TRUE(given.status.ok()) << given.status.error_message();
  EXPECT_EQ(unset.Mesh(), given.Mesh()) << "unset must mean the defaults 11 bits, level 7";

  v1::Parameters lossless;
  lossless.set_quantization(0);
  lossless.set_compression_level(0);
  const CallResult zero = Reconstruct(cloud, lossless);
  ASSERT_TRUE(zero.status.ok()) << zero.status.error_message();
  EXPECT_NE(StatisticsOf(zero).find("\"requested_bits\": 0"), std::string::npos)
      << StatisticsOf(zero);
  EXPECT_GT(zero.Mesh().size(), 2 * unset.Mesh().size()) << "0 bits must be lossless float32";
}

// Unset bits are the server's to choose: 11, raised on grids too wide for them (as `membrane
// reconstruct` does when --quantization is not given); bits a client sets stand as set.
TEST(ParameterChecks, UnsetQuantizationFollowsTheVoxelAndSetQuantizationStands) {
  absl::StatusOr<server::JobSettings> unset = server::CheckParameters(v1::Parameters(), 0);
  ASSERT_TRUE(unset.ok()) << unset.status();
  EXPECT_EQ(unset->reconstruction.output_quantization_bits, 11);
  EXPECT_TRUE(unset->reconstruction.output_bits_follow_voxel);

  v1::Parameters eleven;
  eleven.set_quantization(11);
  absl::StatusOr<server::JobSettings> given = server::CheckParameters(eleven, 0);
  ASSERT_TRUE(given.ok()) << given.status();
  EXPECT_EQ(given->reconstruction.output_quantization_bits, 11);
  EXPECT_FALSE(given->reconstruction.output_bits_follow_voxel);

  v1::Parameters ply;
  ply.set_mesh_format(v1::MESH_FORMAT_PLY);
  absl::StatusOr<server::JobSettings> lossless = server::CheckParameters(ply, 0);
  ASSERT_TRUE(lossless.ok()) << lossless.status();
  EXPECT_EQ(lossless->reconstruction.output_quantization_bits, 0);
}

// A client's voxel plan reaches the run as given; one without a voxel size, or with a formula
// size or noise out of range, is INVALID_ARGUMENT naming voxel_plan.
TEST(ParameterChecks, VoxelPlanIsPassedOnAndCheckedByField) {
  v1::Parameters p;
  p.set_voxel_size(0.02);
  p.mutable_voxel_plan()->set_formula_voxel_size(0.01);
  p.mutable_voxel_plan()->set_point_noise(0.003);
  absl::StatusOr<server::JobSettings> planned = server::CheckParameters(p, 0);
  ASSERT_TRUE(planned.ok()) << planned.status();
  ASSERT_TRUE(planned->reconstruction.voxel_plan.has_value());
  EXPECT_EQ(planned->reconstruction.voxel_plan->formula_voxel_size, 0.01);
  EXPECT_EQ(planned->reconstruction.voxel_plan->point_noise, 0.003);
  EXPECT_FALSE(server::CheckParameters(v1::Parameters(), 0)->reconstruction.voxel_plan);

  auto message_of = [](const v1::Parameters& bad) {
    absl::StatusOr<server::JobSettings> s = server::CheckParameters(bad, 0);
    EXPECT_EQ(s.status().code(), absl::StatusCode::kInvalidArgument);
    return std::string(s.status().message());
  };
  v1::Parameters no_size = p;
  no_size.set_voxel_size(0);
  EXPECT_EQ(message_of(no_size),
            "voxel_plan needs the voxel_size it planned: voxel_size is 0 (the server's default)");
  v1::Parameters zero = p;
  zero.mutable_voxel_plan()->set_formula_voxel_size(0);
  EXPECT_EQ(message_of(zero), "voxel_plan formula_voxel_size 0 is out of range: finite, > 0");
  v1::Parameters nan = p;
  nan.mutable_voxel_plan()->set_point_noise(std::nan(""));
  EXPECT_EQ(message_of(nan), "voxel_plan point_noise nan is out of range: finite, >= 0");
  v1::Parameters negative = p;
  negative.mutable_voxel_plan()->set_point_noise(-1);
  EXPECT_EQ(message_of(negative), "voxel_plan point_noise -1 is out of range: finite, >= 0");
}

}  // namespace
}  // namespace membrane::testing
