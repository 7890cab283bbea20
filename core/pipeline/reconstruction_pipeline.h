// The reconstruction proper, from a point cloud in memory to a checked triangle mesh:
// voxelize, shrink, relax, surface, check. Reading the input and writing the output are the
// caller's (a file for `membrane reconstruct --local`, an upload for the server), so both run
// this one function and give the same mesh for the same cloud and options.
#ifndef MEMBRANE_CORE_PIPELINE_RECONSTRUCTION_PIPELINE_H_
#define MEMBRANE_CORE_PIPELINE_RECONSTRUCTION_PIPELINE_H_

#include <functional>

#include "absl/status/statusor.h"
#include "core/engine/cancel_token.h"
#include "core/engine/membrane_shrinker.h"
#include "core/engine/voxelization.h"
#include "core/geometry/point_cloud.h"
#include "core/geometry/triangle_mesh.h"
#include "core/pipeline/reconstruction_observer.h"
#include "core/pipeline/reconstruction_report.h"
#include "core/pipeline/surface_builder.h"
#include "core/pipeline/thread_limits.h"

namespace membrane {

struct ReconstructionOptions {
  VoxelizeOptions voxelize;
  ShrinkOptions shrink;
  bool relax = true;
  SurfaceKind surface = SurfaceKind::kSmooth;
  // The grid the delivery quantizes positions to (Draco position bits, 0..30; 0: float32 as
  // they are). The surface is built on that grid and checked there, so the report describes
  // the positions delivered, not positions the encoding then moves.
  int output_quantization_bits = 0;
  // Threads of the smooth surface's fit and of the mesh check, 1..kMaxReconstructionThreads;
  // the other stages use the calling thread. The mesh is the same for any value.
  int threads = 1;
  // Asked once the membrane is final, before the surface is built, with its counts (the
  // statistics' "membrane", taken before relaxation, which moves few voxels); a non-OK status
  // ends the reconstruction with it. The server reserves the surface's memory here
  // (SurfaceBytesEstimate, memory_estimate.h): a noisy cloud's surface can take many times
  // its grid's bytes.
  // Empty: the surface is built without asking.
  std::function<absl::Status(const MembraneCounts& membrane)> admit_surface;
};

struct ReconstructionResult {
  TriangleMesh mesh;  // model units, outward faces, with the cloud's origin
  // Every measurement but seconds.decode and, without a MeshDelivery, seconds.encode (left 0
  // for the caller);
  // seconds.total spans the five stages here, peak_rss_bytes is this process's peak so far.
  ReconstructionReport report;
};

// Reconstructs the surface of `cloud` with `options`, telling `observer` of each stage and
// each plate generation. The result holds the mesh even when the check finds it not closed
// or not manifold (the caller decides what that means: see report.mesh).
// Errors, with the core's messages (callers add their own context, such as a file name or a
// flag to change): InvalidArgument for a degenerate cloud (no points, all equal, coplanar) or
// invalid options; ResourceExhausted for a grid over options.voxelize.voxel_budget; Cancelled
// when `cancel` fires (polled within the shrink, the relaxation and the smooth surface, and
// between stages, so a cancel takes effect within milliseconds).
//
// `deliver`, when given, is the caller's encoding or writing of the mesh, given the grid its
// positions lie on (report.quantization): it runs on this thread while the check runs on a
// thread of its own (both only read the mesh), so that neither waits for the other; then the
// encode stage is reported to `observer` with its own wall seconds in report.seconds.encode
// (which overlap seconds.check). A non-OK status from it is the reconstruction's.
// When the check finds crossing or flattened faces on a quantizing grid, the surface is built
// again in float32 and checked and delivered again (report.quantization.bits 0; the delivery
// is then called twice, and the second call's output is the one to keep).
using MeshDelivery =
    std::function<absl::Status(const TriangleMesh& mesh, const PositionGrid& grid)>;
absl::StatusOr<ReconstructionResult> ReconstructCloud(const PointCloud& cloud,
                                                      const ReconstructionOptions& options,
                                                      const CancelToken& cancel,
                                                      ReconstructionObserver& observer,
                                                      const MeshDelivery& deliver = nullptr);

}  // namespace membrane

#endif  // MEMBRANE_CORE_PIPELINE_RECONSTRUCTION_PIPELINE_H_
