// The software rasterizer of previews (core/render/mesh_views.h) and its PNG files: pixels of
// known meshes, checked one by one.
#include "core/render/mesh_views.h"

#include <cmath>

#include <gtest/gtest.h>

#include "core/render/png_codec.h"
#include "tests/mesh/mesh_builders.h"

namespace membrane {
namespace {

using testing::Concat;
using testing::CubeMesh;
using testing::TorusMesh;

constexpr int kN = 64;                  // the side of each view
constexpr uint32_t kBackground = 0x20262f;

// How many pixels of view `v` (0 front, 1 side, 2 above) are not the background.
int Covered(const RgbImage& image, int v) {
  int covered = 0;
  for (int y = 0; y < kN; ++y) {
    for (int x = 0; x < kN; ++x) covered += image.At(v * kN + x, y) != kBackground;
  }
  return covered;
}

// The hue family of a colour: which of its channels is largest.
int Dominant(uint32_t rgb) {
  const int r = (rgb >> 16) & 0xff, g = (rgb >> 8) & 0xff, b = rgb & 0xff;
  return r >= g && r >= b ? 0 : g >= b ? 1 : 2;
}

TEST(MeshViews, ACubeFills90PercentOfEachViewWithBackgroundAround) {
  const RgbImage image = RenderMeshViews(CubeMesh(), {kN, kBackground});
  ASSERT_EQ(image.width, 3 * kN);
  ASSERT_EQ(image.height, kN);
  for (int v = 0; v < 3; ++v) {
    // A square of 0.9 * 64 = 57.6 pixels: 57 or 58 pixel centres a side.
    EXPECT_GE(Covered(image, v), 57 * 57) << "view " << v;
    EXPECT_LE(Covered(image, v), 58 * 58) << "view " << v;
    EXPECT_EQ(image.At(v * kN, 0), kBackground);
    EXPECT_EQ(image.At(v * kN + kN - 1, kN - 1), kBackground);
    EXPECT_NE(image.At(v * kN + kN / 2, kN / 2), kBackground);
  }
}

TEST(MeshViews, AFaceIsShadedByItsAngleToTheLight) {
  const RgbImage image = RenderMeshViews(CubeMesh(), {kN, kBackground});
  // The front view sees the face y = 0, normal (0, -1, 0), lit from toward + up/2 - right*0.4:
  // (-0.4, -1, 0.5) normalised, so the colour is scaled by 0.3 + 0.7 / |(-0.4, -1, 0.5)|.
  const double intensity = 0.3 + 0.7 / std::sqrt(0.16 + 1 + 0.25);
  const uint32_t base = kShellColours[0];
  const uint32_t centre = image.At(kN / 2, kN / 2);
  for (int shift = 16; shift >= 0; shift -= 8) {
    EXPECT_EQ(static_cast<long>((centre >> shift) & 0xff),
              std::lround(((base >> shift) & 0xff) * intensity))
        << "channel " << shift;
  }
  // Every pixel of the face has that shade: one flat face, one colour.
  EXPECT_EQ(image.At(kN / 4, kN / 4), centre);
  EXPECT_EQ(image.At(3 * kN / 4, 3 * kN / 4), centre);
}

TEST(MeshViews, ShellsHaveTheirOwnColoursAndTheNearestFaceWins) {
  // A small cube in front of a large one: the front view shows the small one (shell 1) at its
  // centre, the large one (shell 0) around it; from the side, both side by side.
  const TriangleMesh mesh = Concat(CubeMesh({0, 2, 0}, 3), CubeMesh({1, -1, 1}, 1));
  const RgbImage image = RenderMeshViews(mesh, {kN, kBackground});
  const uint32_t centre = image.At(kN / 2, kN / 2);
  // 10 pixels up is 1.04 units (the scale is 0.9 * 64 / 6 pixels a unit): z = 2.54, above the
  // small cube (z <= 2), inside the large one (z <= 3).
  const uint32_t around = image.At(kN / 2, kN / 2 - 10);
  EXPECT_NE(centre, kBackground);
  EXPECT_NE(around, kBackground);
  EXPECT_EQ(Dominant(centre), Dominant(kShellColours[1]));  // orange
  EXPECT_EQ(Dominant(around), Dominant(kShellColours[0]));  // blue
}

TEST(MeshViews, FacesSmallerThanAPixelLeaveNoHoles) {
  // A torus about z of 160,000 faces, most of them holding no pixel centre: seen from above it
  // is the annulus between radii 0.7 and 1.3, every pixel centre inside it covered and every
  // one outside left as background (a pixel and a half of margin for the polygon's facets).
  const RgbImage image = RenderMeshViews(TorusMesh(400, 200, 1.0f, 0.3f), {kN, kBackground});
  const double scale = 0.9 * kN / 2.6;  // pixels a unit: the box's largest side is 2.6
  const double margin = 1.5 / scale;
  int inside = 0;
  for (int y = 0; y < kN; ++y) {
    for (int x = 0; x < kN; ++x) {
      const double d = std::hypot(x + 0.5 - kN / 2.0, y + 0.5 - kN / 2.0) / scale;
      const uint32_t pixel = image.At(2 * kN + x, y);
      if (d > 0.7 + margin && d < 1.3 - margin) {
        ++inside;
        EXPECT_NE(pixel, kBackground) << "hole at (" << x << ", " << y << ")";
      } else if (d < 0.7 - margin || d > 1.3 + margin) {
        EXPECT_EQ(pixel, kBackground) << "drawn at (" << x << ", " << y << ")";
      }
    }
  }
  EXPECT_GT(inside, 1000);
}

TEST(MeshViews, NothingToDrawGivesTheBackground) {
  TriangleMesh bad;
  bad.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  bad.faces = {{0, 1, 7}, {0, 0, 0}};  // out of range; no area
  for (const TriangleMesh& mesh : {TriangleMesh{}, bad}) {
    const RgbImage image = RenderMeshViews(mesh, {kN, kBackground});
    for (int v = 0; v < 3; ++v) EXPECT_EQ(Covered(image, v), 0);
  }
}

TEST(PngCodec, RoundTripKeepsEveryPixel) {
  const RgbImage image = RenderMeshViews(TorusMesh(24, 12, 1.0f, 0.3f), {kN, kBackground});
  const absl::StatusOr<std::string> png = EncodePng(image);
  ASSERT_TRUE(png.ok()) << png.status();
  EXPECT_EQ(png->substr(1, 3), "PNG");
  const absl::StatusOr<RgbImage> back = DecodePng(*png);
  ASSERT_TRUE(back.ok()) << back.status();
  EXPECT_EQ(back->width, image.width);
  EXPECT_EQ(back->height, image.height);
  EXPECT_EQ(back->pixels, image.pixels);
  // The torus' hole: background at the centre of the view from above.
  EXPECT_EQ(image.At(2 * kN + kN / 2, kN / 2), kBackground);
  EXPECT_GT(Covered(image, 2), kN * kN / 4);
}

TEST(PngCodec, RefusesWhatIsNotAPicture) {
  EXPECT_EQ(DecodePng("not a png").status().code(), absl::StatusCode::kInvalidArgument);
  RgbImage wrong(4, 4, 0);
  wrong.pixels.resize(5);
  EXPECT_EQ(EncodePng(wrong).status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_EQ(EncodePng(RgbImage()).status().code(), absl::StatusCode::kInvalidArgument);
}

}  // namespace
}  // namespace membrane
