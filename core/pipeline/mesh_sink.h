// Where a reconstruction's mesh goes: a file, a Draco encoding in memory. The pipeline runs it
// as its encode stage, beside the mesh check (RunReconstruction, reconstruction_pipeline.h).
#ifndef MEMBRANE_CORE_PIPELINE_MESH_SINK_H_
#define MEMBRANE_CORE_PIPELINE_MESH_SINK_H_

#include "absl/status/status.h"
#include "core/geometry/point_cloud.h"
#include "core/geometry/position_grid.h"
#include "core/geometry/triangle_mesh.h"

namespace membrane {

class MeshSink {
 public:
  virtual ~MeshSink() = default;

  // Called once the cloud is read, before any reconstruction, with its origin
  // (PointCloud::origin): a sink that cannot put a mesh there (a file of float32 positions for
  // a cloud its reader moved) says so now rather than after the work. A non-OK status ends
  // the run as it is. By default every origin is accepted.
  virtual absl::Status CheckOrigin(const Origin3d& /*origin*/) { return absl::OkStatus(); }

  // Takes the mesh: model units, outward faces, the cloud's origin, its positions on `grid`
  // (the output grid the surface was built on; lossless: float32). Called on the
  // reconstructing thread while the mesh check reads the same mesh on a thread of its own, so
  // it must only read `mesh`. Called a second time when the check finds crossing or flattened
  // faces on a quantizing grid that the surface step did not know of (KnownBroken): the
  // surface is then built again in float32, and the second mesh replaces the first. A non-OK status ends the run as it is. Not polled for cancel
  // (an encoding or a write is short); the pipeline looks at the token after it.
  virtual absl::Status Write(const TriangleMesh& mesh, const PositionGrid& grid) = 0;
};

}  // namespace membrane

#endif  // MEMBRANE_CORE_PIPELINE_MESH_SINK_H_
