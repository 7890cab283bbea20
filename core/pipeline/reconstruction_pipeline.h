// The one driver of a reconstruction, from where the cloud comes from to where the mesh goes:
// decode, voxelize, shrink, relax, surface, check and encode, each timed and told to an
// observer, the memory admitted before it is taken. `membrane reconstruct --local`, membraned
// and the benchmarks run this function; they differ only in their adapters (a file or an
// upload in, a memory limit or a shared budget, a file or a Draco result out), so they give
// the same mesh for the same cloud and options.
#ifndef MEMBRANE_CORE_PIPELINE_RECONSTRUCTION_PIPELINE_H_
#define MEMBRANE_CORE_PIPELINE_RECONSTRUCTION_PIPELINE_H_

#include "absl/status/statusor.h"
#include "core/base/cancel_token.h"
#include "core/pipeline/cloud_source.h"
#include "core/pipeline/error_context.h"
#include "core/pipeline/mesh_sink.h"
#include "core/pipeline/reconstruction_observer.h"
#include "core/pipeline/reconstruction_options.h"
#include "core/pipeline/reconstruction_report.h"
#include "core/pipeline/resource_gate.h"

namespace membrane {

// The caller's side of a run. Not owned; each must outlive the run. All are called on the
// reconstructing thread, except that the mesh check runs beside `sink` (see MeshSink).
struct PipelineAdapters {
  CloudSource& source;               // the decode stage
  ResourceGate& gate;                // admits the grid's memory, then the surface's
  MeshSink& sink;                    // the encode stage
  ReconstructionObserver& observer;  // told of every stage and plate generation
};

// Reads the cloud from adapters.source, reconstructs its surface with `options` and writes
// the mesh to adapters.sink. Returns every measurement (report.seconds of all eight stages
// and their total, peak_rss_bytes of this process so far). The mesh is written and the
// report returned even when the check finds the mesh not closed or not manifold: the caller
// decides what that means (see report.mesh).
//
// Order: options checked; decode (the source); the sink's CheckOrigin; the grid planned
// (PlanGrid) and admitted (the gate); voxelize, shrink, relax; the surface admitted (the
// gate); surface; decimate (with options.target_faces); check beside encode (the sink). When the check finds crossing or flattened
// faces on a quantizing grid, surface, check and encode run again in float32
// (report.quantization.bits 0).
//
// Errors: the adapters' statuses as they are. The pipeline's own, with `errors` added
// (WithErrorContext): InvalidArgument for options out of range, a degenerate cloud (no
// points, all equal, coplanar), an options.grid_box that is not finite, flat, inverted or
// does not hold the points (PlanGrid), a cloud that gives no surface or a face target below
// what its surface's topology needs; ResourceExhausted for a grid
// over options.voxelize.voxel_budget or whose estimate is over options.memory_ceiling_bytes
// (CheckMemoryCeiling); Cancelled "reconstruction cancelled after STAGE" when
// `cancel` fires. The token is polled within the source, the gate, the shrink, the
// relaxation, the smooth surface and the check, and between stages, so a cancel takes effect
// within milliseconds (the sink alone is not polled).
absl::StatusOr<ReconstructionReport> RunReconstruction(const ReconstructionOptions& options,
                                                       const PipelineAdapters& adapters,
                                                       const ErrorContext& errors,
                                                       const CancelToken& cancel);

}  // namespace membrane

#endif  // MEMBRANE_CORE_PIPELINE_RECONSTRUCTION_PIPELINE_H_
