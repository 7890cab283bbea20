#include "tests/support/plane_edge_cloud.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include <gtest/gtest.h>

#include "core/engine/point_density.h"
#include "core/engine/voxelization.h"
#include "core/io/draco_codec.h"
#include "core/synth/synthesize.h"

namespace membrane::testing {

PlaneEdgeCloud MakePlaneEdgeCloud(int points, int bits) {
  PlaneEdgeCloud c;
  c.bits = bits;
  absl::StatusOr<PointCloud> cloud =
      SynthesizeShape(SynthOptions{.shape = "sphere", .points = points, .seed = 1});
  EXPECT_TRUE(cloud.ok()) << cloud.status();
  if (!cloud.ok()) return c;
  c.cloud = *std::move(cloud);
  DracoOptions draco;
  draco.position_quantization_bits = bits;
  absl::StatusOr<DracoEncoding> encoded = EncodeDracoPointCloud(c.cloud, draco);
  EXPECT_TRUE(encoded.ok()) << encoded.status();
  if (!encoded.ok()) return c;
  absl::StatusOr<DecodedDracoCloud> decoded = DecodeDracoPointCloud(encoded->bytes);
  EXPECT_TRUE(decoded.ok()) << decoded.status();
  if (!decoded.ok()) return c;
  c.quantized = std::move(decoded->cloud);
  absl::StatusOr<Box3d> box = CheckedBounds(c.cloud.points);
  absl::StatusOr<Box3d> quantized_box = CheckedBounds(c.quantized.points);
  EXPECT_TRUE(box.ok() && quantized_box.ok());
  if (!box.ok() || !quantized_box.ok()) return c;
  c.box = *box;
  c.quantized_box = *quantized_box;
  const auto extent = c.box.Extent();
  const auto quantized_extent = c.quantized_box.Extent();
  double moved = 0;
  for (int d = 0; d < 3; ++d) {
    const double m = std::fabs(extent[d] - quantized_extent[d]);
    if (m > moved) {
      moved = m;
      c.axis = d;
    }
  }
  const double range = std::max({extent[0], extent[1], extent[2]});
  const double step = range / (std::ldexp(1.0, bits) - 1);
  // Far above float32's rounding of coordinates near 1, so that the planes fall apart clearly.
  EXPECT_GT(moved, step / 20) << "Draco moved no extreme point";
  // 24 voxels end between the two extents, halfway.
  c.voxel_size = (extent[c.axis] + quantized_extent[c.axis]) / 2 / 24;
  EXPECT_LE(step, c.voxel_size / 8);
  c.data_dims = DataDims(c.box, c.voxel_size);
  c.quantized_data_dims = DataDims(c.quantized_box, c.voxel_size);
  EXPECT_EQ(std::abs(c.data_dims[c.axis] - c.quantized_data_dims[c.axis]), 1);
  return c;
}

}  // namespace membrane::testing
