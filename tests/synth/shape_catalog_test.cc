// The shape list and the true topology the engine's tests compare against.
#include "core/synth/shape_catalog.h"

#include "gmock/gmock.h"
#include "gtest/gtest.h"

namespace membrane {
namespace {

using ::testing::ElementsAre;

TEST(SynthShapeNamesTest, ListsTheFiveShapesInHelpOrder) {
  EXPECT_THAT(SynthShapeNames(),
              ElementsAre("sphere", "two-spheres", "torus", "capped-sphere", "cube-pinholes"));
}

TEST(ExpectedTopologyTest, GivesShellsAndGenusOfEveryShape) {
  const auto check = [](const std::string& shape, int shells, std::vector<int> genus) {
    const ShapeTopology t = ExpectedTopology(shape);
    EXPECT_EQ(t.shells, shells) << shape;
    EXPECT_EQ(t.genus, genus) << shape;
  };
  check("sphere", 1, {0});
  check("two-spheres", 2, {0, 0});
  check("torus", 1, {1});
  check("capped-sphere", 1, {0});
  check("cube-pinholes", 1, {0});
}

TEST(ExpectedTopologyTest, UnknownShapeHasNoShells) {
  const ShapeTopology t = ExpectedTopology("cone");
  EXPECT_EQ(t.shells, 0);
  EXPECT_TRUE(t.genus.empty());
}

}  // namespace
}  // namespace membrane
