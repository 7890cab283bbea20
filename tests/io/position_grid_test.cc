// The quantization grid the surface is snapped to, against what Draco stores and decodes:
// positions on the grid must come back bit for bit, or the mesh check judged other positions
// than the file holds.
#include "core/geometry/position_grid.h"

#include <algorithm>
#include <random>
#include <vector>

#include "core/io/draco_codec.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "tests/support/io_test_util.h"

namespace membrane {
namespace {

using ::testing::HasSubstr;

// A grid whose box holds [low, low + side]^3, built as the pipeline builds it.
PositionGrid GridAround(int bits, double low, double side) {
  PositionGrid grid;
  grid.bits = bits;
  for (int k = 0; k < 3; ++k) grid.box.origin[k] = DecimalSafeBound(low, /*lower=*/true);
  grid.box.range = DecimalSafeBound(low + side - grid.box.origin[0], /*lower=*/false);
  return grid;
}

TEST(PositionGrid, DecimalSafeBoundsSurviveDracosOptionTextOnTheirSide) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> mantissa(1, 10);
  for (int i = 0; i < 2000; ++i) {
    const double x = (i % 2 ? -1 : 1) * mantissa(rng) * std::pow(10.0, i % 12 - 6);
    for (bool lower : {true, false}) {
      const float f = DecimalSafeBound(x, lower);
      EXPECT_EQ(DecimalRoundTrip(f), f) << x;
      EXPECT_TRUE(lower ? f <= x : f >= x) << x;
      // Close: within a millionth (the text's last digit) and a float step.
      EXPECT_LE(std::fabs(f - x), 1.1e-6 + 4 * std::fabs(x) * 1.2e-7) << x;
    }
  }
}

TEST(PositionGrid, SnapIsIdempotentAndStaysInTheBox) {
  const PositionGrid grid = GridAround(11, -3.2, 6.7);
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> coord(-4.f, 4.f);
  for (int i = 0; i < 10000; ++i) {
    const Point3f p{coord(rng), coord(rng), coord(rng)};
    const Point3f s = grid.Snap(p);
    EXPECT_EQ(grid.Snap(s), s);
    for (int k = 0; k < 3; ++k) {
      EXPECT_GE(s[k], grid.box.origin[k]);
      EXPECT_LE(s[k], grid.box.origin[k] + grid.box.range * (1 + 1e-6f));
    }
  }
  EXPECT_EQ(PositionGrid{}.Snap({0.1f, 0.2f, 0.3f}), (Point3f{0.1f, 0.2f, 0.3f}));
}

TEST(PositionGrid, SnappedMeshComesBackFromDracoBitForBit) {
  // Boxes of several magnitudes and offsets; an origin that does not survive Draco's option
  // text moved every decoded vertex by up to 3e-7 before DecimalSafeBound.
  const TriangleMesh sphere = testing::SphereMesh(24, 48);
  for (const auto& [low, side] : std::vector<std::pair<double, double>>{
           {-0.0641592517, 5.38369656}, {12.5499372, 2.0}, {-2.73823833, 0.01}, {1000.3, 40}}) {
    for (int bits : {8, 11, 16}) {
      const PositionGrid grid = GridAround(bits, low, side);
      TriangleMesh mesh = sphere;
      for (Point3f& p : mesh.vertices) {
        for (int k = 0; k < 3; ++k) p[k] = static_cast<float>(low + side * (0.5 + 0.45 * p[k]));
        p = grid.Snap(p);
      }
      const absl::StatusOr<DracoEncoding> encoded =
          EncodeDracoMesh(mesh, DracoOptionsOnGrid(grid, 7));
      ASSERT_TRUE(encoded.ok()) << encoded.status();
      const absl::StatusOr<TriangleMesh> decoded = DecodeDracoMesh(encoded->bytes);
      ASSERT_TRUE(decoded.ok()) << decoded.status();
      std::vector<Point3f> want = mesh.vertices, got = decoded->vertices;
      std::sort(want.begin(), want.end());
      std::sort(got.begin(), got.end());
      EXPECT_EQ(got, want) << "box at " << low << " side " << side << ", " << bits << " bits";
    }
  }
}

TEST(PositionGrid, DracoRefusesPositionsOutsideTheBoxAndBoxesThatAreNotFinite) {
  TriangleMesh mesh = testing::Octahedron();
  const PositionGrid grid = GridAround(11, 0.0, 1.0);  // the octahedron spans [-1, 1]
  const absl::StatusOr<DracoEncoding> encoded = EncodeDracoMesh(mesh, DracoOptionsOnGrid(grid, 7));
  EXPECT_EQ(encoded.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(encoded.status().message(), HasSubstr("outside the quantization box"));
  DracoOptions bad = DracoOptionsOnGrid(grid, 7);
  bad.box->range = 0;
  EXPECT_EQ(ValidateDracoOptions(bad).code(), absl::StatusCode::kInvalidArgument);
  bad.box->range = 1;
  bad.box->origin[1] = std::numeric_limits<float>::quiet_NaN();
  EXPECT_THAT(ValidateDracoOptions(bad).message(), HasSubstr("quantization box"));
}

}  // namespace
}  // namespace membrane
