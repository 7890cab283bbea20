#include "core/pipeline/memory_estimate.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <limits>

#include "absl/status/status.h"
#include "absl/strings/str_format.h"
#include "core/engine/voxel_grid.h"
#include "core/pipeline/grid_box.h"
#include "core/pipeline/machine_memory.h"

namespace membrane {
namespace {

// One stage's bytes: a fixed part plus so many bytes per voxel of the grid, per point of the
// cloud and per boundary voxel of the final membrane. Figures from bench_memory (see
// EstimateStageBytes), rounded up.
struct StageCost {
  double fixed;
  double per_voxel;
  double per_point;
  double per_membrane_voxel;
};

// The process besides its data: code, libraries, the allocator's arenas, threads' stacks (3-15
// MB measured before a run; the rest is margin for the stages' small structures).
constexpr double kProcessBytes = 32e6;
// The decoded cloud: float32 x, y, z. Every stage holds it.
constexpr double kCloudBytes = 12;

// Measured with bench_memory on a torus of 1M and 2M points (7.0e7 and 2.0e8 voxels, 0.77 and
// 1.55 boundary voxels a point), each stage's peak fitted to the grid, the cloud and the
// membrane, then rounded up; uniform noise checks the surface's share (below).
// Decode: the cloud.
constexpr StageCost kDecode = {kProcessBytes, 0, kCloudBytes, 0};
// Voxelize: the grid (1 byte a voxel), the points' sorted voxels (8 bytes a point); formula
// (1)'s copy of the points grouped by hash before it (12 bytes a point, freed before the grid).
constexpr StageCost kVoxelize = {kProcessBytes, 1, kCloudBytes + 36, 0};
// The shrink: the grid (1 byte a voxel), 8 work planes (1 bit a voxel each), the anchors of
// the last snapshot kept as packed copies (place_finder.h: 0.54 bytes a voxel measured at 1M
// points, 0.41 at 2M, less on larger grids, whose rows of words are longer than the membrane's
// crossings), and the handle retry's checkpoints as runs of equal bytes (a small fraction of a
// byte a voxel): 2.6 bytes a voxel; and the points indexed by voxel for the thin-part test
// (HardVoxelPoints: 24 bytes a point at most, 40 while it is built, before any plane).
constexpr StageCost kShrink = {kProcessBytes, 2.6, kCloudBytes + 24, 0};
// The relaxation: the grid, and lists of boundary voxels (8 bytes each, twice while the scan's
// plane lists are joined; 1.7 MB over the grid and the cloud on a 1M-point torus).
constexpr StageCost kRelax = {kProcessBytes, 1, kCloudBytes, 32};
// The surface takes the membrane's grid (the pipeline keeps it as runs of equal bytes, a
// hundredth of a byte a voxel on the torus: 0.05 allows for more) and holds, one step after
// the other: the clean-up on the grid itself with the cave filling's two bit masks (1.25
// bytes a voxel; the loose sheets' one bit mask before them). The surface nets: the cleaned
// grid, the voxel boundary's quads and fan vertices (64 bytes a boundary voxel, up to three
// times that while their arrays grow) and the mesh with its fallback positions (48 more). The
// fit, the grid freed: the fit's point index (0.4 bytes a voxel measured) and the mesh and the
// fit's structures (580 bytes a boundary voxel on the torus, 600 on 100k points of uniform
// noise, whose foam of a membrane has 2.2 faces a boundary voxel).
constexpr StageCost kSurfaceCleanUp = {kProcessBytes, 1.35, kCloudBytes, 0};
constexpr StageCost kSurfaceNets = {kProcessBytes, 1.15, kCloudBytes, 250};
constexpr StageCost kSurfaceFit = {kProcessBytes, 0.45, kCloudBytes, 800};
// The check and the encoding beside it: the grid's runs, the mesh, the check's and the
// encoder's structures (340-390 bytes a boundary voxel on the torus, 380 on noise).
constexpr StageCost kCheck = {kProcessBytes, 0.05, kCloudBytes, 500};

int64_t Bytes(const StageCost& cost, int64_t voxels, int64_t points, int64_t membrane_voxels) {
  // In double: a planned grid can hold 9e18 voxels before any budget caps it.
  const double bytes = cost.fixed + cost.per_voxel * static_cast<double>(voxels) +
                       cost.per_point * static_cast<double>(points) +
                       cost.per_membrane_voxel * static_cast<double>(membrane_voxels);
  return static_cast<int64_t>(std::min(bytes, 9e18));
}

}  // namespace

absl::StatusOr<PlannedGrid> PlanGrid(const PointCloud& cloud, const VoxelizeOptions& voxelize,
                                     const CancelToken& cancel,
                                     const std::optional<Box3d>& grid_box) {
  if (grid_box) {
    if (absl::Status s = CheckGridBox(*grid_box); !s.ok()) return s;
  }
  absl::StatusOr<Box3d> points_bounds = CheckedBounds(cloud.points, cancel);
  if (cancel.cancelled()) {
    return absl::CancelledError("reconstruction cancelled while planning the grid");
  }
  if (!points_bounds.ok()) return points_bounds.status();
  // Everything below reads the grid's box, which is the points' own unless one is given.
  const Box3d* bounds = grid_box ? &*grid_box : &*points_bounds;
  PlannedGrid plan;
  plan.bounds = *bounds;
  plan.voxel_size = voxelize.voxel_size;
  if (plan.voxel_size <= 0) {
    plan.formula_voxel_size = FormulaVoxelSize(*bounds, cloud.points, voxelize.threads, cancel);
    plan.voxel_size = plan.formula_voxel_size;
    // Read at formula (1)'s voxel, and once more at the voxel that reading gives when it is
    // coarser: noise over half a voxel reads low in cubes 4 voxels wide (their sides cut the
    // tails), and the coarser cubes read it whole.
    for (int reading = 0; reading < 2 && !cancel.cancelled(); ++reading) {
      plan.noise = MeasurePointNoise(cloud.points, *bounds, kNoiseBoxVoxels / 2 * plan.voxel_size,
                                     cancel);
      const double size = NoiseAwareVoxelSize(plan.formula_voxel_size, plan.noise);
      if (size <= plan.voxel_size) break;
      plan.voxel_size = size;
    }
    // The count or the noise stopped short: the size means nothing.
    if (cancel.cancelled()) {
      return absl::CancelledError("reconstruction cancelled while planning the grid");
    }
  }
  if (grid_box) {
    if (absl::Status s = CheckGridBoxHoldsPoints(*grid_box, *points_bounds, plan.voxel_size);
        !s.ok()) {
      return s;
    }
  }
  plan.voxels = PlannedVoxelCount(*bounds, plan.voxel_size);
  plan.points = static_cast<int64_t>(cloud.points.size());
  const int64_t counted =
      voxelize.voxel_budget > 0 ? std::min(plan.voxels, voxelize.voxel_budget) : plan.voxels;
  plan.bytes = GridBytesEstimate(counted, plan.points);
  return plan;
}

int64_t PlannedVoxelCount(const Box3d& bounds, double voxel_size) {
  double voxels = 1;
  for (const double side : bounds.Extent()) {
    voxels *= std::floor(side / voxel_size) + 1 + 2 * VoxelGrid::kPadding;
  }
  return static_cast<int64_t>(std::min(voxels, 9e18));
}

double SmallestVoxelSizeWithin(const PlannedGrid& grid, int64_t limit_bytes,
                               int64_t voxel_budget) {
  // A plan whose box does not give its voxels was not made by PlanGrid: nothing to scale.
  if (limit_bytes <= 0 || !(grid.voxel_size > 0) ||
      PlannedVoxelCount(grid.bounds, grid.voxel_size) != grid.voxels) {
    return 0;
  }
  const auto fits = [&](double size) {
    const int64_t voxels = PlannedVoxelCount(grid.bounds, size);
    return GridBytesEstimate(voxels, grid.points) <= limit_bytes &&
           (voxel_budget <= 0 || voxels <= voxel_budget);
  };
  if (fits(grid.voxel_size)) return grid.voxel_size;
  // The bytes fall as the size grows (each side's count is a floor): double it up to the size
  // that makes the box one voxel wide, then halve the interval to where it starts to fit.
  const std::array<double, 3> extent = grid.bounds.Extent();
  const double widest = std::max({extent[0], extent[1], extent[2]});
  double over = grid.voxel_size, within = grid.voxel_size;
  while (!fits(within)) {
    over = within;
    within *= 2;
    if (within > 2 * widest) return 0;
  }
  for (int step = 0; step < 60 && within - over > 1e-6 * within; ++step) {
    const double middle = (over + within) / 2;
    (fits(middle) ? within : over) = middle;
  }
  // Up to three significant digits, as the advice prints it, and read back as a user would
  // type it: the decimal, not the double it was printed from, must fit.
  const double unit = std::pow(10.0, std::floor(std::log10(within)) - 2);
  double rounded = std::ceil(within / unit * (1 - 1e-12)) * unit;
  for (int bump = 0; bump < 3; ++bump, rounded += unit) {
    const double typed = std::strtod(absl::StrFormat("%.3g", rounded).c_str(), nullptr);
    if (fits(typed)) return typed;
  }
  return within;
}

absl::Status CheckMemoryCeiling(const PlannedGrid& grid, int64_t ceiling_bytes) {
  std::string what;
  if (ceiling_bytes == -1) {
    const MachineMemory machine = ReadMachineMemory();
    ceiling_bytes = machine.total_bytes;
    what = absl::StrFormat("the %s of memory this machine has (%s)", BytesText(ceiling_bytes),
                           machine.total_source);
  } else {
    what = absl::StrFormat("the ceiling of %s", BytesText(ceiling_bytes));
  }
  if (ceiling_bytes <= 0 || grid.bytes <= ceiling_bytes) return absl::OkStatus();
  const double fitting = SmallestVoxelSizeWithin(grid, ceiling_bytes);
  return absl::ResourceExhaustedError(absl::StrFormat(
      "voxel size %g gives a grid of %.3g voxels: with the %d points it needs about %s, more "
      "than %s%s",
      grid.voxel_size, static_cast<double>(grid.voxels), grid.points, BytesText(grid.bytes),
      what,
      fitting > 0 ? absl::StrFormat(" (voxel size %.3g or larger fits)", fitting) : ""));
}

StageBytes EstimateStageBytes(int64_t voxels, int64_t points, const MembraneCounts& membrane) {
  const int64_t m = membrane.membrane_voxels();
  StageBytes s;
  s.decode = Bytes(kDecode, voxels, points, m);
  s.voxelize = Bytes(kVoxelize, voxels, points, m);
  s.shrink = Bytes(kShrink, voxels, points, m);
  s.relax = Bytes(kRelax, voxels, points, m);
  s.surface = std::max({Bytes(kSurfaceCleanUp, voxels, points, m),
                        Bytes(kSurfaceNets, voxels, points, m),
                        Bytes(kSurfaceFit, voxels, points, m)});
  s.check = Bytes(kCheck, voxels, points, m);
  return s;
}

int64_t GridBytesEstimate(int64_t voxels, int64_t points) {
  const StageBytes s = EstimateStageBytes(voxels, points, MembraneCounts{});
  return std::max({s.decode, s.voxelize, s.shrink, s.relax, s.surface});
}

int64_t SurfaceBytesEstimate(const PlannedGrid& grid, const MembraneCounts& membrane) {
  const StageBytes s = EstimateStageBytes(grid.voxels, grid.points, membrane);
  return std::max(s.surface, s.check);
}

std::string BytesText(int64_t bytes) {
  static constexpr const char* kUnits[] = {"bytes", "KB", "MB", "GB", "TB", "PB", "EB"};
  double value = static_cast<double>(bytes);
  int unit = 0;
  while (std::abs(value) >= 999.5 && unit < 6) {
    value /= 1000;
    ++unit;
  }
  if (unit == 0) return absl::StrFormat("%d bytes", bytes);
  return absl::StrFormat("%.3g %s", value, kUnits[unit]);
}

int64_t DracoTableBytes(int quantization_bits) {
  if (quantization_bits <= 0) return 0;
  return int64_t{4} << std::min(quantization_bits, 30);
}

int64_t SurfacePeakBytes(const PlannedGrid& grid, const MembraneCounts& membrane,
                         int output_quantization_bits) {
  const int64_t peak = std::max(SurfaceBytesEstimate(grid, membrane), grid.bytes);
  const int64_t tables = DracoTableBytes(output_quantization_bits);
  return peak > std::numeric_limits<int64_t>::max() - tables
             ? std::numeric_limits<int64_t>::max()
             : peak + tables;
}

}  // namespace membrane
