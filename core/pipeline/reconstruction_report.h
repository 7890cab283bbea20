// Everything a reconstruction measured: the source of the final table, the summary line and
// the statistics JSON (design/contracts.md).
#ifndef MEMBRANE_CORE_PIPELINE_RECONSTRUCTION_REPORT_H_
#define MEMBRANE_CORE_PIPELINE_RECONSTRUCTION_REPORT_H_

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/engine/gap_refill.h"
#include "core/engine/hole_opening.h"
#include "core/engine/interior_guard.h"
#include "core/engine/membrane_shrinker.h"
#include "core/engine/piece_separation.h"
#include "core/engine/post_process.h"
#include "core/engine/topology_guard.h"
#include "core/mesh/hole_caps.h"
#include "core/mesh/mesh_check.h"
#include "core/mesh/mesh_decimation.h"
#include "core/mesh/point_fitting.h"
#include "core/mesh/relaxation.h"
#include "core/mesh/smooth_surface.h"
#include "core/mesh/surface_deviation.h"
#include "core/pipeline/membrane_counts.h"

namespace membrane {

// Wall-clock seconds per stage. `total` spans all stages, the statistics writing excepted.
struct StageSeconds {
  double decode = 0;  // reading and parsing the input (the run's CloudSource)
  double voxelize = 0;
  double shrink = 0;  // all generations and the section 7 post-process
  double relax = 0;   // 0 with --no-relax
  double surface = 0;
  double decimate = 0;  // 0 without a face budget
  double check = 0;   // CheckMesh of the surface
  double encode = 0;  // encoding and writing the output (the run's MeshSink), beside the check
  double total = 0;
};

// The grid the delivered positions lie on (ReconstructionOptions::output_quantization_bits).
struct QuantizationReport {
  int requested_bits = 0;  // 0: float32 asked for
  // The grid the mesh was built, checked and delivered on: the requested one (with more bits
  // where the voxel needs them and the caller left the bits to the reconstruction:
  // ReconstructionOptions::output_bits_follow_voxel), or 0 (float32) when on it the check
  // found crossing or flattened faces.
  int bits = 0;
  double step = 0;  // model units between grid positions along an axis; 0 for float32
  // How far the grid can move a coordinate from where float32 would put it: half the step (0
  // for float32). The positions delivered are the ones checked, exactly.
  double max_position_error = 0;
};

// The decimate stage (ReconstructionOptions::target_faces): DecimationStats, and the error it
// added: the distance from each vertex of the surface as built to the decimated surface.
struct DecimationReport {
  bool ran = false;  // a face budget was asked for
  DecimationStats stats;
  SurfaceDeviation error;  // model units
};

struct ReconstructionReport {
  int64_t points = 0;
  // The cloud's origin (PointCloud::origin): where the positions' 0 lies in the input's
  // coordinates; every other length here is the same in both.
  std::array<double, 3> origin{0, 0, 0};
  double voxel_size = 0;                     // model units
  // When no voxel size was given: formula (1)'s, and the points' noise across their surface
  // (PointNoise::sigma), both in model units; voxel_size is over formula_voxel_size when the
  // noise raised it (NoiseAwareVoxelSize). Both 0 when the size was given.
  double formula_voxel_size = 0;
  double point_noise = 0;
  std::array<int, 3> grid{};                 // voxels per axis, VoxelGrid::kPadding layers included
  std::array<int, 3> data_grid{};            // voxels per axis covering the points (no padding)
  int64_t hard_voxels = 0;                   // voxels holding points
  double density_ratio = 0;                  // Voxelization::density_ratio
  std::string schedule;                      // "halving" or "linear"
  std::string surface;                       // "smooth" or "cuberille"
  bool relaxed = false;                      // false with --no-relax
  int threads = 1;                           // ReconstructionOptions::threads
  int planned_generations = 0;               // plate sizes of the schedule, known before shrinking
  InteriorGuardStats interior_guard;  // ShrinkResult::interior_guard, before the generations
  CoarsePlatesStats coarse_plates;    // ShrinkResult::coarse_plates, the first generations
  GuardSizes topology_guard;          // ShrinkResult::guard
  std::vector<GenerationStats> generations;  // one per plate size, the last has plate size 1
  PostProcessStats post_process;
  HandleRetry handle_retry;    // ShrinkResult::handle_retry
  // The shrink's passes after the generations, in their order (ShrinkResult::separation,
  // ::holes, ::refill): the grid's topology changes after the last generation are theirs.
  PieceSeparationStats piece_separation;
  HoleOpeningStats hole_opening;
  GapRefillStats gap_refill;
  MembraneCounts membrane;     // the final DMS, before relaxation
  RelaxationStats relaxation;  // all 0 with --no-relax
  HoleCapStats hole_caps;      // the smooth surface's caps over data holes
  FitTargetCounts fit;         // the smooth surface's fit (all 0 for cuberille)
  MeshReport mesh;             // CheckMesh of the surface (vertices and faces set before it)
  DecimationReport decimation;
  QuantizationReport quantization;
  StageSeconds seconds;
  SurfaceStepSeconds surface_seconds;  // the smooth surface's steps (all 0 for cuberille)
  int64_t peak_rss_bytes = 0;  // getrusage ru_maxrss, in bytes
  // What the user should know about the result, one sentence each (ScatterWarning's), in the
  // order found; set before the stage that found them is reported finished.
  std::vector<std::string> warnings;
};

}  // namespace membrane

#endif  // MEMBRANE_CORE_PIPELINE_RECONSTRUCTION_REPORT_H_
