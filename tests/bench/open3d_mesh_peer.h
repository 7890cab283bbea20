// Runs the Open3D Poisson peer (open3d_poisson.py --write-mesh) and reads back its mesh, for
// accuracy measurements (bench_surface). Timing and JSON as RunOpen3dPoisson (open3d_peer.h).
#ifndef MEMBRANE_TESTS_BENCH_OPEN3D_MESH_PEER_H_
#define MEMBRANE_TESTS_BENCH_OPEN3D_MESH_PEER_H_

#include <string>

#include "absl/status/statusor.h"
#include "core/geometry/triangle_mesh.h"
#include "tests/bench/open3d_peer.h"

namespace membrane::bench {

struct Open3dMeshRun {
  Open3dRun run;      // seconds (normals + orient + poisson, wall), faces, the JSON line
  TriangleMesh mesh;  // Poisson's mesh as is (not clipped by density)
};

// Runs peer.script on `cloud_path` with --depth `depth` and --write-mesh to a temporary .ply
// under $TMPDIR (else /tmp), reads it with ReadMesh and deletes it. DeadlineExceeded when
// peer.timeout_seconds > 0 passed first; Internal with the script's output when it fails or
// prints no JSON line; the errors of ReadMesh for an unreadable mesh.
absl::StatusOr<Open3dMeshRun> RunOpen3dPoissonMesh(const Open3dPeer& peer,
                                                   const std::string& cloud_path, int depth = 9);

}  // namespace membrane::bench

#endif  // MEMBRANE_TESTS_BENCH_OPEN3D_MESH_PEER_H_
