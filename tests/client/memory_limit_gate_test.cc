// `membrane reconstruct --local --memory-limit` admits the surface as membraned's memory gate
// does: Draco's encoding tables (2^bits entries, whatever the mesh) count beside the surface.
#include <cstdint>
#include <string>

#include "client/memory_limit_gate.h"
#include "core/pipeline/memory_estimate.h"
#include "gtest/gtest.h"

namespace membrane::client {
namespace {

// A small grid and membrane: well under a gigabyte without the tables.
PlannedGrid SmallGrid() {
  PlannedGrid grid;
  grid.voxels = 1'000'000;
  grid.points = 100'000;
  grid.bytes = GridBytesEstimate(grid.voxels, grid.points);
  return grid;
}

MembraneCounts SmallMembrane() {
  MembraneCounts membrane;
  membrane.soft_voxels = 10'000;
  return membrane;
}

TEST(MemoryLimitGate, TheSurfaceCountsDracosTablesAtThirtyBits) {
  const PlannedGrid grid = SmallGrid();
  const MembraneCounts membrane = SmallMembrane();
  // A limit the surface fits in, but not beside the 4.3 GB of tables of a 30-bit encoding.
  const int64_t limit = SurfaceBytesEstimate(grid, membrane) + (int64_t{1} << 30);
  ASSERT_LT(grid.bytes, limit);

  MemoryLimitGate ply(limit, 0);
  ASSERT_TRUE(ply.AdmitGrid(grid, grid.points, CancelToken::Never()).ok());
  EXPECT_TRUE(ply.AdmitSurface(membrane, CancelToken::Never()).ok());

  MemoryLimitGate drc(limit, 30);
  ASSERT_TRUE(drc.AdmitGrid(grid, grid.points, CancelToken::Never()).ok());
  const absl::Status refused = drc.AdmitSurface(membrane, CancelToken::Never());
  EXPECT_EQ(refused.code(), absl::StatusCode::kResourceExhausted) << refused;
  EXPECT_NE(refused.message().find("Draco encoder's tables"), std::string::npos) << refused;
  EXPECT_NE(refused.message().find("--quantization"), std::string::npos) << refused;
}

TEST(MemoryLimitGate, AdmitsWhatMembranedsGateCounts) {
  const PlannedGrid grid = SmallGrid();
  const MembraneCounts membrane = SmallMembrane();
  const int64_t peak = SurfacePeakBytes(grid, membrane, 30);
  EXPECT_EQ(peak, std::max(SurfaceBytesEstimate(grid, membrane), grid.bytes) +
                      DracoTableBytes(30));
  MemoryLimitGate at(peak, 30);
  ASSERT_TRUE(at.AdmitGrid(grid, grid.points, CancelToken::Never()).ok());
  EXPECT_TRUE(at.AdmitSurface(membrane, CancelToken::Never()).ok());
  MemoryLimitGate below(peak - 1, 30);
  ASSERT_TRUE(below.AdmitGrid(grid, grid.points, CancelToken::Never()).ok());
  EXPECT_FALSE(below.AdmitSurface(membrane, CancelToken::Never()).ok());
}

}  // namespace
}  // namespace membrane::client
