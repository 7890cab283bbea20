// Mesh validity report: what the surface step promises (paper section 6, algorithm-notes 13,
// membrane-quality.md recipe 3): closed, manifold, outward oriented, free of self-intersections,
// with the shells and genus of the membrane. Also what `membrane check MESH` prints
// (design/contracts.md).
#ifndef MEMBRANE_CORE_MESH_MESH_CHECK_H_
#define MEMBRANE_CORE_MESH_MESH_CHECK_H_

#include <array>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "core/base/cancel_token.h"
#include "core/base/progress_meter.h"
#include "core/geometry/triangle_mesh.h"

namespace membrane {

struct MeshReport {
  int64_t vertices = 0;
  int64_t faces = 0;
  // Faces with an index outside [0, vertices): skipped by every other count.
  int64_t invalid_faces = 0;
  // Faces with a repeated index or (relatively) zero area.
  int64_t degenerate_faces = 0;
  // Vertices used by no valid face; left out of the Euler characteristics.
  int64_t unreferenced_vertices = 0;
  int64_t boundary_edges = 0;        // undirected edges in exactly one face
  int64_t nonmanifold_edges = 0;     // undirected edges in three or more faces
  int64_t misoriented_edges = 0;     // edges used twice in the same direction
  int64_t nonmanifold_vertices = 0;  // vertices whose faces form more than one fan
  bool closed = false;               // every edge in exactly two faces
  bool edge_manifold = false;        // no edge in more than two faces
  bool vertex_manifold = false;      // the faces around each vertex form one fan or cycle
  bool manifold = false;             // edge_manifold && vertex_manifold
  bool oriented = false;             // no edge used twice in one direction
  double volume = 0;                 // signed volume, model units^3 (positive = outward)
  bool positive_volume = false;      // every shell encloses a positive signed volume
  // Pairs of faces that intersect. Faces with no common vertex count on any contact
  // (touching included). Faces sharing a vertex or an edge count only on a NON-TRIVIAL
  // overlap: a common point besides the shared vertex, or coplanar faces folded over their
  // shared edge.
  int64_t self_intersections = 0;
  int shells = 0;  // connected components of faces over shared edges
  // Genus of each shell, in shell order (ordered by first face), from V - E + F = 2 - 2g;
  // -1 for a shell that is not closed and manifold (where the formula means nothing).
  std::vector<int> genus;
};

// Whether `face` of `mesh` has no area: a repeated index, or corners on one line (to double
// precision). MeshReport::degenerate_faces counts the faces it is true of.
bool IsDegenerateFace(const TriangleMesh& mesh, const std::array<int32_t, 3>& face);

// Checks `mesh` (vertices in any units; faces index `mesh.vertices`, CCW seen from outside).
// Never fails: malformed input shows up in the counts. O(F) plus a uniform-grid broad phase
// for self-intersections (about a second for 1M faces). `cancel` is polled during the
// self-intersection search; once it fires the search stops early and the report is
// incomplete (the caller, having cancelled, discards it). `threads` (<= 1: the calling thread
// alone) share that search; the report does not depend on it. `known_crossings`, if not null,
// must be FindIntersectingFaces(mesh) as found by whoever searched this very mesh last (the
// smooth surface's fit: FitStats::crossings): the check counts it instead of searching again.
// `progress` counts the passes over faces and vertices, then the search's cells, and reaches
// its end with the check.
MeshReport CheckMesh(const TriangleMesh& mesh, const CancelToken& cancel = CancelToken::Never(),
                     int threads = 1,
                     const std::vector<std::pair<int32_t, int32_t>>* known_crossings = nullptr,
                     ProgressRange progress = ProgressRange());

// The report as one JSON object with snake_case keys ("closed", "manifold", "oriented",
// "shells", "genus": [...], ...), for `membrane check --json` and the statistics JSON.
std::string MeshReportToJson(const MeshReport& report);

}  // namespace membrane

#endif  // MEMBRANE_CORE_MESH_MESH_CHECK_H_
