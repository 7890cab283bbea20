// What a reconstruction computes: the options of its stages.
#ifndef MEMBRANE_CORE_PIPELINE_RECONSTRUCTION_OPTIONS_H_
#define MEMBRANE_CORE_PIPELINE_RECONSTRUCTION_OPTIONS_H_

#include <cstdint>
#include <optional>

#include "core/engine/membrane_shrinker.h"
#include "core/engine/voxelization.h"
#include "core/geometry/point_cloud.h"
#include "core/pipeline/surface_builder.h"
#include "core/pipeline/thread_limits.h"

namespace membrane {

// How a given voxel size was chosen on the cloud as its owner read it (PlanGrid's
// formula_voxel_size and noise.sigma), for a run on a quantized copy of it (membraned's
// uploads), so that the run reports and treats the voxel as the owner's own run would.
struct VoxelPlanNote {
  double formula_voxel_size = 0;  // > 0
  double point_noise = 0;         // >= 0
};

struct ReconstructionOptions {
  // voxel_size 0: formula (1)'s, which the pipeline computes once when it plans the grid.
  VoxelizeOptions voxelize;
  // The box the grid is planned on instead of the points' own (grid_box.h): the box of the
  // cloud as its owner read it, when the points are a quantized copy (membraned's uploads).
  // The points must lie within 1/kGridBoxStepsPerVoxel of the voxel outside it.
  std::optional<Box3d> grid_box;
  // With voxelize.voxel_size > 0: how that size was planned (Parameters.voxel_plan). The
  // report's formula_voxel_size and point_noise are these, and a size over formula_voxel_size
  // is the noise's (VoxelRaisedForNoise: the shrink guards the interior as a dense scan's).
  // Ignored when the size is left to the run, which plans it itself.
  std::optional<VoxelPlanNote> voxel_plan;
  ShrinkOptions shrink;
  bool relax = true;
  SurfaceKind surface = SurfaceKind::kSmooth;
  // The grid the mesh sink quantizes positions to (Draco position bits, 0..30; 0: float32 as
  // they are). The surface is built on that grid and checked there, so the report describes
  // the positions delivered, not positions the encoding then moves.
  int output_quantization_bits = 0;
  // The caller left the bits to the reconstruction: output_quantization_bits is raised where
  // the grid is so wide that its step would exceed kMaxOutputStepVoxels (OutputBitsForVoxel).
  bool output_bits_follow_voxel = false;
  // Threads of the stages that split their work by the geometry (the voxelization, the
  // shrink's word passes, the relaxation's passes, the smooth surface, the mesh check, the
  // decimation's error measure; docs/design.md, "Threads"), 1..kMaxReconstructionThreads.
  // The mesh is the same for any value.
  int threads = 1;
  // At most this many faces in the mesh delivered (>= kMinTargetFaces), or as few as keeping
  // it closed, manifold, outward, uncrossed and of the same topology allows: the decimate
  // stage (mesh_decimation.h). 0: the surface as built.
  int64_t target_faces = 0;
  // The most memory a run may be planned to take, whatever its ResourceGate admits
  // (CheckMemoryCeiling): -1, the machine's; 0, none; else bytes.
  int64_t memory_ceiling_bytes = -1;
};

}  // namespace membrane

#endif  // MEMBRANE_CORE_PIPELINE_RECONSTRUCTION_OPTIONS_H_
