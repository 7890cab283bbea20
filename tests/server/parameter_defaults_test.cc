// Parameters a client leaves unset get the server's defaults, and 0 set explicitly means 0:
// a client written from the .proto alone gets the mesh `membrane reconstruct` would.
#include <string>

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace membrane::testing
