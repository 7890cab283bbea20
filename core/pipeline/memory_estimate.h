// What a reconstruction will hold in memory, estimated before it allocates: stage by stage,
// from the grid and the cloud before voxelizing, and from the membrane before the surface. A
// run's peak is the largest stage's, not their sum: each stage frees its working sets before
// the next begins. The server's memory budget and `membrane reconstruct --local`'s memory
// limit refuse a job on these numbers, before the kernel's OOM killer would end it; the
// pipeline refuses a grid over the machine's memory whatever the gate.
#ifndef MEMBRANE_CORE_PIPELINE_MEMORY_ESTIMATE_H_
#define MEMBRANE_CORE_PIPELINE_MEMORY_ESTIMATE_H_

#include <cstdint>
#include <optional>
#include <string>

#include "absl/status/statusor.h"
#include "core/base/cancel_token.h"
#include "core/engine/point_noise.h"
#include "core/engine/voxelization.h"
#include "core/geometry/point_cloud.h"
#include "core/pipeline/membrane_counts.h"

namespace membrane {

// The side, in formula-(1) voxels, of the cubes the default voxel size reads the points' noise
// in (MeasurePointNoise's half-width is half of it).
inline constexpr double kNoiseBoxVoxels = 4;

// The grid Voxelize will allocate for `cloud` with `voxelize`, computed the same way before
// anything is allocated.
struct PlannedGrid {
  Box3d bounds;           // CheckedBounds of the points, or the grid box PlanGrid was given
  // voxelize.voxel_size when > 0, else NoiseAwareVoxelSize of formula (1)'s and the noise
  // (model units).
  double voxel_size = 0;
  // When voxelize.voxel_size is 0: formula (1)'s size, and the points' noise as last read: in
  // cubes kNoiseBoxVoxels formula-(1) voxels on a side, then, when that reading raised the
  // voxel, in cubes kNoiseBoxVoxels raised voxels on a side. Both 0 when the size was given.
  double formula_voxel_size = 0;
  PointNoise noise;
  int64_t voxels = 0;     // padding included
  int64_t points = 0;     // the cloud's
  // GridBytesEstimate of the grid and the points; a grid over a positive voxelize.voxel_budget
  // counts at the budget (Voxelize refuses it, with the grid in its message, before
  // allocating).
  int64_t bytes = 0;
};
// Formula (1), when voxelize.voxel_size is 0, counts the points on voxelize.threads threads,
// and MeasurePointNoise reads their noise (one or two more passes over them).
// InvalidArgument for a degenerate cloud (CheckedBounds' message). Callers that then voxelize
// pass the planned voxel_size and bounds on (VoxelizeOptions::voxel_size, checked_bounds), so
// that formula (1) does not count the points again nor Voxelize check them again.
// Cancelled when `cancel` fires during the point check or the count (CheckedBounds and
// DistinctPointCount ask it) or the noise's pass.
// With `grid_box` (grid_box.h), the grid is planned on that box instead of the points' own:
// `bounds` is the box, formula (1) and the noise read it, and the points are still checked;
// InvalidArgument (CheckGridBox's, CheckGridBoxHoldsPoints' message) for a box that is not
// finite, is flat or inverted, or does not hold the points within 1/kGridBoxStepsPerVoxel of
// the planned voxel.
absl::StatusOr<PlannedGrid> PlanGrid(const PointCloud& cloud, const VoxelizeOptions& voxelize,
                                     const CancelToken& cancel = CancelToken::Never(),
                                     const std::optional<Box3d>& grid_box = std::nullopt);

// The voxels of a grid on `bounds` with voxels of `voxel_size` > 0, padding included, as
// PlanGrid counts them (saturating at 9e18).
int64_t PlannedVoxelCount(const Box3d& bounds, double voxel_size);

// For a refusal's advice: the smallest voxel size at or above grid.voxel_size, given to three
// significant digits, whose grid on grid.bounds (PlannedVoxelCount) with grid.points has a
// GridBytesEstimate within `limit_bytes` and, when voxel_budget > 0, at most that many voxels.
// grid.voxel_size itself when it fits; 0 when no size does (the points alone are over the
// limit, or a limit <= 0) or the plan is not PlanGrid's (grid.voxels is not its box's count).
double SmallestVoxelSizeWithin(const PlannedGrid& grid, int64_t limit_bytes,
                               int64_t voxel_budget = 0);

// The most a planned grid may need whatever the run's gate admits: ResourceExhausted "voxel size
// L gives a grid of V voxels: with the P points it needs about B, more than the M of memory
// this machine has (SOURCE) (voxel size S or larger fits)" when `grid.bytes` is over the
// ceiling, S being SmallestVoxelSizeWithin the ceiling (left out when none fits). `ceiling_bytes` -1: the
// machine's memory (ReadMachineMemory's total_bytes; no check when unknown); 0: none; else the
// ceiling itself (named "the ceiling of M" then). Such a grid could never be allocated: without
// this check a run without a memory limit would end in the kernel's OOM killer instead.
absl::Status CheckMemoryCeiling(const PlannedGrid& grid, int64_t ceiling_bytes);

// The bytes a run holds at the peak of each stage, the process's own (code, libraries) and the
// cloud's included: what its peak RSS would read if the stage ran alone. Measured against the
// kernel's high-water mark stage by stage in tests/bench/bench_memory.cc (torus, 100k to 10M
// points; uniform noise), each at or above the measured peak.
struct StageBytes {
  int64_t decode = 0;    // the decoded cloud (a file reader's own buffers are the source's)
  int64_t voxelize = 0;  // the grid, the points' sorted voxels, formula (1)'s distinct points
  int64_t shrink = 0;    // the grid and the shrink's bit planes
  int64_t relax = 0;     // the grid and the relaxation's three byte arrays
  int64_t surface = 0;   // the grid, and its copy cleaned up for the surface, then the mesh and fit
  int64_t check = 0;     // the grid, the mesh, the check's and the encoder's structures
};
// `membrane` is only read for the surface and check stages (zero counts: their grid share).
StageBytes EstimateStageBytes(int64_t voxels, int64_t points, const MembraneCounts& membrane);

// The peak of the stages before the surface (decode, voxelize, shrink, relax) and of the
// surface's share that the grid alone decides (its clean-up: the grid, its copy and two bit
// masks, with no membrane counted): what is admitted before the grid is allocated, so that no
// run is refused at its surface for bytes the grid already told. Saturates instead of
// overflowing.
int64_t GridBytesEstimate(int64_t voxels, int64_t points);

// The peak of the stages from the surface on (surface, decimate, check, encode) for the
// membrane of `grid`'s run, the grid itself included: what must fit once the membrane is
// known. The surface of uniform noise (a foam of a membrane: 1.8-2.7 faces per boundary voxel)
// takes many times its grid's bytes.
int64_t SurfaceBytesEstimate(const PlannedGrid& grid, const MembraneCounts& membrane);

// The bytes Draco's encoder holds in its tables of 2^bits entries, whatever the mesh: 4 an
// entry (a 1M-point torus's mesh peaked 3.56 GB higher at 30 bits than at 11, 3.3 bytes an
// entry; tests/bench/2026-12-03-download-memory.txt); 0 for bits 0 (float32 positions).
int64_t DracoTableBytes(int quantization_bits);

// The most a run holds from the surface on, what a gate admits once the membrane is known:
// the larger of the grid's and the surface's estimates (the surface's counts the grid held
// beside it), plus Draco's tables when the mesh is encoded at `output_quantization_bits`
// (ReconstructionOptions::output_quantization_bits; 0: float32 or not Draco). Saturates
// instead of overflowing.
int64_t SurfacePeakBytes(const PlannedGrid& grid, const MembraneCounts& membrane,
                         int output_quantization_bits);

// `bytes` for a person: "512 KB", "38.1 MB", "2.61 GB" (powers of 1000, 3 significant digits).
std::string BytesText(int64_t bytes);

}  // namespace membrane

#endif  // MEMBRANE_CORE_PIPELINE_MEMORY_ESTIMATE_H_
