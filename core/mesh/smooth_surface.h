// The default `smooth` surface of a membrane (paper section 6; algorithm-notes 13;
// membrane-quality.md recipes 2 and 3): clean-up on a copy of the grid, surface nets, fitting to
// the points.
#ifndef MEMBRANE_CORE_MESH_SMOOTH_SURFACE_H_
#define MEMBRANE_CORE_MESH_SMOOTH_SURFACE_H_

#include <cstdint>

#include "absl/status/statusor.h"
#include "absl/types/span.h"
#include "core/base/cancel_token.h"
#include "core/base/progress_meter.h"
#include "core/engine/voxel_grid.h"
#include "core/geometry/point_cloud.h"
#include "core/geometry/triangle_mesh.h"
#include "core/mesh/hole_caps.h"
#include "core/mesh/point_fitting.h"

namespace membrane {

struct SmoothSurfaceOptions {
  bool remove_loose_sheets = true;  // recipe 3 step 1
  bool fill_caves = true;           // recipe 2
  int bridging_scans = 3;           // recipe 3 step 2 (0 = off)
  bool fit = true;                  // recipe 3 steps 5-6
  HoleCapOptions hole_caps;         // with the fit only: before it
  FitOptions fit_options;
};

// Wall seconds of SmoothSurface's steps: where a large cloud's surface time goes.
struct SurfaceStepSeconds {
  double prepare = 0;  // the clean-up of the membrane: loose sheets, caves, diagonal bridges
  double nets = 0;     // the surface nets (with the fit: before their repair)
  double caps = 0;     // the caps over data holes
  double fit = 0;      // the fit to the points, its crossing repair included
};

struct SmoothSurfaceStats {
  int64_t loose_sheet_voxels = 0;    // voxels of removed loose sheets
  int64_t cave_voxels = 0;           // voxels filled in caves
  int64_t bridges = 0;               // voxels added at corner-only contacts
  int64_t corner_contacts_left = 0;  // contacts no simple voxel could bridge
  HoleCapStats caps;
  FitStats fit;
  SurfaceStepSeconds seconds;
};

// Input: the final (optionally relaxed) membrane, read only; `points` the input cloud in model
// units. The steps, in order, on a copy of the grid: loose-sheet removal (loose_sheets.h; first,
// so that cave filling cannot thicken a sheet into something kept), homotopic cave filling
// (cave_filling.h), diagonal-contact bridging (diagonal_bridging.h); then the surface nets,
// with the fit CapHoles() (hole_caps.h: smooth caps over the gaps in the data) and
// FitToPoints(). With the fit, the nets' crossing repair is left to the fit's final check
// (SurfaceNetsBeforeRepair), so the whole mesh is searched once.
// Cost, measured on a 200^3 ball with 150k points (324k faces) on the shared 2-core machine:
// about 1 s in all, 0.7 s of it the fit.
// Output: a closed, manifold, outward-oriented mesh without self-intersections, in model
// units, whose shells and genus are those of the membrane's solid minus any removed loose
// sheets (caves and bridges are filled homotopically), unless `corner_contacts_left` > 0.
// `stats` may be null. `progress` counts the steps and the fit's work, and reaches its end
// when the surface is done. Errors: InvalidArgument for bad fit options; Cancelled when
// `cancel` fired.
absl::StatusOr<TriangleMesh> SmoothSurface(const VoxelGrid& membrane,
                                           absl::Span<const Point3f> points,
                                           const SmoothSurfaceOptions& options = {},
                                           SmoothSurfaceStats* stats = nullptr,
                                           const CancelToken& cancel = CancelToken::Never(),
                                           ProgressRange progress = ProgressRange());

// The same from a membrane the caller gives up: the clean-up works on `membrane` itself, and
// its bytes (one a voxel) are freed once the surface nets are made, so that the caps and the
// fit hold the mesh and the points alone. `membrane` is left empty (a default VoxelGrid)
// whatever the outcome. The same mesh and stats as the copying overload.
absl::StatusOr<TriangleMesh> SmoothSurface(VoxelGrid&& membrane,
                                           absl::Span<const Point3f> points,
                                           const SmoothSurfaceOptions& options = {},
                                           SmoothSurfaceStats* stats = nullptr,
                                           const CancelToken& cancel = CancelToken::Never(),
                                           ProgressRange progress = ProgressRange());

}  // namespace membrane

#endif  // MEMBRANE_CORE_MESH_SMOOTH_SURFACE_H_
