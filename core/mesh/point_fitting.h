// Fitting the surface-nets vertices to the input points without ever breaking the mesh
// (membrane-quality.md recipe 3 steps 5-6; algorithm-notes 13, "fit the vertices to the points
// with a per-vertex back-off that keeps the mesh free of self-intersections, also after
// rounding to float32").
#ifndef MEMBRANE_CORE_MESH_POINT_FITTING_H_
#define MEMBRANE_CORE_MESH_POINT_FITTING_H_

#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include "absl/status/statusor.h"
#include "absl/types/span.h"
#include "core/base/cancel_token.h"
#include "core/base/progress_meter.h"
#include "core/geometry/point_cloud.h"
#include "core/geometry/position_grid.h"
#include "core/geometry/triangle_mesh.h"
#include "core/mesh/crease_fit.h"
#include "core/mesh/height_quadric.h"
#include "core/mesh/point_row_grid.h"

namespace membrane {

// Lengths in voxels (multiples of the membrane's voxel size).
struct FitOptions {
  int rounds = 4;              // passes over all vertices
  double search_radius = 2.0;  // points gathered within this distance of the vertex
  double sigma = 1.0;          // Gaussian weight of a point's distance
  // From the second round, a point's offset along the vertex normal is weighted with this
  // (narrower) sigma instead, so the opposite sheet of a thin part does not pull.
  double normal_sigma = 0.6;
  int min_points = 6;          // fewer points: umbrella step instead of a plane fit
  // Curved targets: the projection on a height-field quadric fitted in the vertex's frame
  // (height_quadric.h) where at least quadric_min_points points are near and the quadric
  // passes quadric_limits; the plane elsewhere. Off: the plane wherever min_points are near.
  bool quadric = true;
  int quadric_min_points = 10;
  HeightQuadricLimits quadric_limits;
  // Where fewer than quadric_min_points points are within search_radius (sparse data), the
  // quadric is tried once more on the points within sparse_radius, weighted with
  // sparse_sigma (0: no second try).
  double sparse_radius = 4.0;
  double sparse_sigma = 2.0;
  // Creases: where the 2-voxel quadric leaves a large residual (or bends past its limits),
  // two planes fitted to the same points (crease_fit.h) give the target when the limits take
  // them: on their line of intersection near it, else on their envelope.
  bool creases = true;
  CreaseLimits crease_limits;
  // A dense cloud (at least dense_points_per_vertex points per mesh vertex: a scan at a voxel
  // its noise raised) is weighed as the means of its points per cell of search_radius /
  // mean_split voxels, each weighted by its count (point_cell_means.h: the cells of an index
  // of search_radius, the caps' gap search's, cut mean_split times along each axis), so that
  // the fit's cost follows the faces and not the points. Infinity: every point always.
  double dense_points_per_vertex = 4;
  int mean_split = 3;
  double umbrella_step = 0.5;  // fraction of the way to the 1-ring mean
  double max_offset = 1.5;     // a vertex never moves farther from its surface-nets position
  double min_move = 1e-3;      // smaller moves are not worth a check
  // The positions that will be delivered (in model units, not voxels): every position the fit
  // writes is snapped to this grid first, so that its checks judge the positions a decoder
  // gets back. Lossless (bits 0): float32.
  PositionGrid output_grid;
  // Threads fitting slabs side by side and sharing the crossing search (<= 1: the calling
  // thread alone). The mesh is the same for any value.
  int threads = 1;
};

// How the fit's targets were made, over all rounds (FitStats' counts, for the run's report).
struct FitTargetCounts {
  int64_t quadric = 0;
  int64_t plane = 0;
  int64_t crease = 0;       // two planes at a crease
  int64_t crease_line = 0;  // of those, on the planes' line of intersection
  int64_t umbrella = 0;
};

struct FitStats {
  int64_t quadric_targets = 0;    // targets from a quadric fit (over all rounds)
  int64_t plane_targets = 0;      // targets from a plane fit (over all rounds)
  int64_t crease_targets = 0;     // targets from two planes at a crease (over all rounds)
  int64_t crease_line_targets = 0;  // of those, on the planes' line of intersection
  int64_t crease_tries = 0;       // targets whose points were fitted with two planes
  int64_t umbrella_targets = 0;   // targets from the umbrella step
  int64_t moves = 0;              // moves kept
  int64_t refused = 0;            // targets not taken even at 1/4 of the way
  int64_t backed_off = 0;         // moves kept at 1/2 or 1/4 of the way
  int64_t repaired_vertices = 0;  // vertex moves toward the fallback (input crossings)
  // The points the fit weighed: the cloud's, or a dense cloud's cell means.
  int64_t weighed_points = 0;
  // True when the final search started from every face (a fallback or a quantizing grid):
  // `crossings` is then every pair of faces of the returned mesh that intersect, as
  // FindIntersectingFaces() lists them (sorted, as (lower, higher) face index), so a mesh
  // check need not search again. Empty otherwise.
  bool crossings_known = false;
  std::vector<std::pair<int32_t, int32_t>> crossings;
};

// Input: `mesh` as SurfaceNets() makes it (closed, manifold, outward, no self-intersections),
// in model units; `voxel_size` > 0 the membrane's voxel edge; `points` the input cloud (model
// units). `cancel` is polled every few thousand vertices.
// Effect: moves vertices only (faces unchanged), in `rounds` passes over the vertices (each pass
// fits slabs 4 voxels thick across the longest axis, the even ones and then the odd ones, each in
// vertex index order; SurfaceNets numbers vertices along a space-filling curve; the slabs of one
// parity run side by side on options.threads): target = the point of the weighted height-field
// quadric of the points near the vertex, in the frame of its normal, above or below it
// (options.quadric, >= quadric_min_points of them and within the limits; with fewer, the same from
// the points within sparse_radius; where the 2-voxel quadric, fitted or refused, leaves a residual
// that two planes explain, options.creases, the point of their crease line near the vertex or of
// their envelope above it: crease_fit.h), else the projection on their weighted PCA plane (>=
// min_points of them), else an umbrella step (a dense cloud's points weighed as their cell means,
// each counting its points: options.dense_points_per_vertex); the target is clamped to max_offset
// from the vertex's input position; the move is tried at 1, 1/2, 1/4 of the way and taken at the
// first where every triangle of the vertex keeps a non-zero area and a positive dot product with
// its input normal, and no two of them overlap. The last pass ends with an intersection search
// around the faces the passes moved, on the float32 positions that are written, on output_grid (so
// it is also recipe step 6's rounding check, and the check of the encoding's quantization): the
// moved vertices of every crossing pair back off through 1/2, 1/4 of the way, then to where they
// started, until nothing crosses. Checking once at the end instead of once per move costs one
// linear search instead of a grid query per vertex, and gives the same guarantee. The result does
// not depend on options.threads.
// `fallback`, if not null, holds one position per vertex at which the mesh is known free of
// self-intersections (SurfaceNetsBeforeRepair's); the input may then cross itself: that
// search covers every face, and crossings that no move explains are repaired toward
// `fallback` (halfway up to 6 times, then all the way, as crossing_repair.h does); the
// repaired positions then count as the vertices' input positions.
// With a quantizing output_grid every vertex is first snapped to it (the input normals stay
// those of the unsnapped input) and that search covers every face.
// After: closed, manifold and oriented as before; every vertex on output_grid; no
// self-intersections if the input had none (lossless grid) or `fallback` was given, unless the
// grid is too coarse for any repair (the caller's mesh check tells); every vertex within
// max_offset * voxel_size of its input position, plus half a grid step per axis.
// `progress` counts the vertices the rounds fit, then the final search, and reaches its end
// when the fit does. `points_grid`, if given, is the PointRowGrid of `points` with cells of
// search_radius voxels (the caps' gap search's), from which a dense cloud's means are taken
// instead of building it; it is released before the rounds.
// Errors: InvalidArgument for a non-positive voxel size, options out of range or a fallback of
// the wrong size; Cancelled when `cancel` fired (the mesh then holds the last verified state:
// every move is undone).
absl::StatusOr<FitStats> FitToPoints(TriangleMesh& mesh, double voxel_size,
                                     absl::Span<const Point3f> points,
                                     const FitOptions& options = {},
                                     const CancelToken& cancel = CancelToken::Never(),
                                     const std::vector<Point3f>* fallback = nullptr,
                                     ProgressRange progress = ProgressRange(),
                                     std::optional<PointRowGrid> points_grid = std::nullopt);

}  // namespace membrane

#endif  // MEMBRANE_CORE_MESH_POINT_FITTING_H_
