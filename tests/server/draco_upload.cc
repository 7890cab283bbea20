#include "tests/server/draco_upload.h"

#include <utility>

#include <gtest/gtest.h>

#include "core/io/draco_codec.h"
#include "core/synth/synthesize.h"

namespace membrane::testing {

std::string LosslessDracoCloud(const std::string& shape, int points) {
  SynthOptions synth;
  synth.shape = shape;
  synth.points = points;
  absl::StatusOr<PointCloud> cloud = SynthesizeShape(synth);
  EXPECT_TRUE(cloud.ok()) << cloud.status();
  if (!cloud.ok()) return "";
  DracoOptions lossless;
  lossless.position_quantization_bits = 0;
  absl::StatusOr<DracoEncoding> encoded = EncodeDracoPointCloud(*cloud, lossless);
  EXPECT_TRUE(encoded.ok()) << encoded.status();
  if (!encoded.ok()) return "";
  return std::move(encoded->bytes);
}

}  // namespace membrane::testing
