// Caps over data holes: where the scanner saw nothing, the membrane sinks into the hole (or cuts
// a protrusion flat) and the surface nets follow it. A smooth cap spans each such gap region of
// the surface from its rim instead, as the smoothness term of a Poisson reconstruction does
// (docs/surface-decisions.md, "Caps over data holes").
#ifndef MEMBRANE_CORE_MESH_HOLE_CAPS_H_
#define MEMBRANE_CORE_MESH_HOLE_CAPS_H_

#include <cstdint>

#include "absl/status/statusor.h"
#include "absl/types/span.h"
#include "core/base/cancel_token.h"
#include "core/geometry/point_cloud.h"
#include "core/geometry/triangle_mesh.h"
#include "core/mesh/point_row_grid.h"

namespace membrane {

// Lengths in voxels (multiples of the membrane's voxel size).
struct HoleCapOptions {
  bool enabled = true;
  // A vertex with no input point within gap_radius lies in a gap (the fit's search radius:
  // sparse data is not a gap).
  double gap_radius = 2.0;
  // Gaps with fewer vertices are left to the fit: a crease of the surface nets, not a hole.
  int min_gap_vertices = 8;
  // A grown gap region that holds more than this share of its shell's vertices is left: a
  // hole is bounded by data that describe the surface around it, and where most of a shell is
  // gap the points scatter about it (a voxel far below their spacing), not a scan with holes.
  // Such a region's "rim" is a few points scattered through it: the cap's plane and spline
  // mean nothing there, lift it tens of voxels and cost the whole surface many times over.
  double max_shell_share = 0.5;
  // Caps need data dense at the gap radius: when the median vertex on the data (one with a
  // point within gap_radius) has fewer than this many points within gap_radius, the points
  // lie about as far apart as that radius (a voxel far below their spacing), a vertex with
  // none near is the spacing between points, not a hole, and no region is capped.
  int min_median_points = 6;
  // Each gap region grows by this many rings of faces before it is capped: the vertices beside
  // a gap lie on the membrane's wall down into the hole, not on the data, and a cap held by
  // them would keep the wall's slope.
  int rim_rings = 3;
  // Points with no vertex within gap_radius (seen through the gap, with the membrane's floor
  // under them: a cap from the rim alone would bury them) hold the cap: the nearest vertex
  // within anchor_radius, when it is a cap's, is held at the mean of its such points. Farther
  // points are not a cap's to reach.
  bool anchor_remote_points = true;
  double anchor_radius = 8.0;
  // A cap held by such points is solved to convergence, holds included (at most
  // wrapped_iterations, see converged_tolerance): thin_plate_iterations from a start that
  // ignores the holds (the harmonic map or the spline) leave a tent around each held vertex,
  // where the converged plate carries the points seen inside the gap across it. Unless the
  // cap from its rim alone says the converged plate leaves the surface: made without the
  // holds, the converged plate passes farther from the held points, on average, than the
  // thin_plate_iterations plate by more than held_margin voxels (the walls' slope carried
  // past an open flat base into a bulge); then the thin_plate_iterations cap stays. That
  // trial's converged plate is solved exactly, by a sparse Cholesky factor
  // (sparse_cholesky.h), where the factor holds at most 4M entries; a larger cap takes
  // conjugate gradients to `tolerance`, at most wrapped_iterations.
  bool converge_held = true;
  double held_margin = 0.5;
  // The cap's vertices are spread by the harmonic (minimal membrane) map of the region with
  // every other vertex fixed, by conjugate gradients: at most this many iterations, stopping
  // once no step moves a vertex by more than `tolerance`.
  int harmonic_iterations = 100;
  double tolerance = 0.01;
  // The cap's shape: the thin-plate spline height field, over the plane of the rim, through
  // the fixed vertices within sample_rings rings of the region (at most max_samples of them,
  // evenly picked), with this smoothing (voxels squared).
  int sample_rings = 3;
  int max_samples = 128;
  double smoothing = 1.0;
  // A rim that turns away from its plane (a sample's normal at or below this cosine with the
  // plane's normal) is no height field over it: there the thin plate starts from the
  // harmonic map instead.
  double min_rim_cosine = -0.25;
  // Then conjugate-gradient iterations toward the discrete thin plate over the region (the
  // graph bi-Laplacian zero at each cap vertex): they mend what the height field cannot
  // follow (a rim not in one plane, a saddle) and join the cap to the rim smoothly.
  int thin_plate_iterations = 60;
  // A rim that is no height field and leaves its plane (the samples' RMS distance from it
  // above wrap_rms voxels) wraps around a part the hole swallowed, the end of a post or the
  // edge of a thin part: the harmonic map cuts straight through that part, and the thin plate
  // is solved to convergence (at most wrapped_iterations, see converged_tolerance), which
  // carries the walls of the rim across the hole. A rim in its plane (an open flat base, whose
  // band of sample_rings rings runs down the side walls within about that many voxels of the
  // plane) keeps the harmonic map's flat span with thin_plate_iterations: the converged thin
  // plate would carry the walls' slope past the base and bulge. Each cap solved to
  // convergence (wrapped, or held: converge_held) is its own system: its iterations and its
  // stopping test are its own, whatever other caps the mesh has.
  double wrap_rms = 3.0;
  int wrapped_iterations = 1000;
  // A cap solved to convergence with more than coarse_plate_vertices vertices (past the sparse
  // factor's size: a 10M-point scan's open base) would take the conjugate gradients hundreds
  // of thousands of iterations, their count growing with the square of its width: its 1000
  // leave it near its start, where a 100k-point cloud's cap of the same part converges. It
  // starts from the plate of its vertices clustered by cells of the fewest whole voxels that
  // leave at most coarse_plate_clusters clusters, solved exactly (the coarse plate), then
  // takes at most coarse_plate_iterations steps toward converged_tolerance (within
  // wrapped_iterations), which smooth the cells' steps. The held caps' trial plate takes the
  // coarse plate where the factor cannot hold it. coarse_plate_clusters: 1 to 2^24.
  int64_t coarse_plate_vertices = int64_t{1} << 17;
  int64_t coarse_plate_clusters = int64_t{1} << 16;
  int coarse_plate_iterations = 200;
  // A wrapped rim around a post or the edge of a thin part whose end the hole swallowed runs
  // on past the rim: its band of sample_rings rings is square to the axis from the band's
  // centroid toward the middle of the cap (the mean of (normal . axis)^2 over the band at most
  // tube_flatness), and the cap lies ahead of the band along that axis by at least tube_lead
  // of the band's mean distance from it (the tube's radius). Then the converged plate, a dome
  // about half a radius high over such a rim, is swept on by swept_length radii along the
  // walls (each rim vertex's direction into the hole along its tangent plane, carried over
  // the cap by the harmonic map), its first rim_rings rings spread along the way: the walls
  // run on into a rounded end, as a smooth surface through the band does. A cap held by
  // points seen inside its gap is swept only where those points agree: the swept cap's
  // vertices (the held ones aside) pass no farther from the held points, on average, than the
  // converged plate's by more than held_margin voxels; otherwise the points tell that the part
  // ends nearer, and the converged plate stays.
  double tube_flatness = 0.25;
  double tube_lead = 0.1;
  double swept_length = 0.75;
  // A cap shaped by the spline (its rim a height field) around a post whose end the hole
  // swallowed (the same tube test: a leg's hoof, the tip of a horn) is swept on too, by
  // spline_swept_length radii: the spline already lifts such a cap along the walls' slope
  // into a dome, and a sweep as long as a wrapped rim's carries it past the part's end. Its
  // rim vertices move along the tube's axis (their normal part taken off), not toward the
  // middle of the cap: round a height-field rim the walls run along the axis, and the
  // directions toward the middle lean in across them and carry the cap less far.
  double spline_swept_length = 0.25;
  // A wrapped cap's region can hold a thin tube of the mesh: a tunnel a voxel or two across
  // that the shrink left through the solid, its walls far from any data, joined to the hole
  // it runs from. Solved with the cap, its walls stand as the rim of the plate (their slope
  // carried into a bulge past the base around them) and the tube couples the cap to its far
  // end. Its vertices (those whose tube_rings-ring neighbourhood in the mesh holds fewer than
  // half the vertices of a flat patch's, 3 k (k + 1) + 1, grown by rim_rings rings within the
  // region) are solved apart, as their own converging system after the rest of the cap.
  // 0: no test.
  int tube_rings = 10;
  // The solves to convergence stop once no step moves a vertex by more than this: the
  // bi-Laplacian's steps fall below `tolerance` hundreds of iterations before the plate
  // settles (a cap of 1,588 vertices: 144 iterations at 0.01 voxel, 398 at 0.001, 589 at
  // 0.0001, the last two the same cap within the scorer's resolution).
  double converged_tolerance = 0.001;
  // A cap shaped by the spline (its rim a height field) is also solved to convergence when the
  // band's own extrapolation says the converged plate is the better cap: the algebraic sphere
  // of the band (algebraic_sphere.h: the fixed vertices within sample_rings rings and their
  // normals) lies within sphere_band_fit voxels of the band on average, and the converged
  // plate's gap vertices (no point within gap_radius) lie closer to that sphere, on average,
  // than those of the thin_plate_iterations cap by more than sphere_margin voxels. Where the
  // sphere does not describe the band (a saddle, an open base, a band over several parts), the
  // thin_plate_iterations cap stays.
  double sphere_band_fit = 2.0;
  double sphere_margin = 0.05;
  // A concave corner under the hole (a belly meeting a leg), which a smooth cap spans as a
  // fillet outside it: where the membrane stayed outside the cap (its mean offset over the
  // cap's gap vertices, along their normals, over corner_membrane_margin voxels outward, three
  // times the surface nets' half-voxel offset from the data: the shrink's plates could not
  // enter there), the band (the fixed vertices within sample_rings rings) is read around each
  // gap vertex in corner_sectors sectors (beyond corner_reach voxels by cells,
  // corner_crease.h), each side the tangent plane of its corner_neighbours nearest band
  // vertices carried into the hole. Where two opposite sides are flat or convex
  // (their sector's band vertices at most corner_flat_tolerance voxels outside the plane on
  // average), lie at least corner_angle degrees apart, each outside the other's plane, and
  // the vertex lies outside both, it moves inward along their normals' mean to the first
  // plane (the longest such move over the pairs, at most corner_max_move voxels): the sides
  // meet in a crease, the boundary of the union of their solids (corner_crease.h). The
  // band's normals are averaged over corner_normal_rings rings (the surface nets'
  // staircase). The moves are then spread over the cap by corner_smoothing steps, each
  // replacing half of a vertex's move by its neighbours' mean (the rim's and the held
  // vertices' moves 0): where a pair of sides stops qualifying, the move jumps and the faces
  // across the jump fold. Over 180 degrees: no crease.
  double corner_angle = 45.0;
  int corner_sectors = 12;
  int corner_neighbours = 3;
  double corner_flat_tolerance = 1.0;
  double corner_max_move = 12.0;
  double corner_reach = 64.0;
  double corner_membrane_margin = 1.5;
  int corner_normal_rings = 2;
  int corner_smoothing = 5;
  // Where two faces of the caps cross (a cap folded over itself, or two caps), the cap
  // vertices of the pair and those within untangle_rings rings of them in the caps take
  // untangle_iterations steps each to their neighbours' mean, round after round of the
  // crossing search, before anything is sent back: a fold is the cap's own layout (the
  // surface nets' vertices drawn together where the cap is creased or pulled down onto a
  // seen surface), and sending its vertices back toward the surface nets hangs the cap
  // toward them, outside the solid. A region still folded after untangle_rounds rounds goes
  // back to its cap as solved, for the back-off (a cap crossing itself all over, where the
  // mean of the neighbours would spread it into a sheet). 0: every crossing backs off.
  int untangle_rounds = 16;
  int untangle_rings = 1;
  int untangle_iterations = 3;
  // A cap vertex of a face that crosses another goes back toward its place before the cap:
  // halfway this many times, then all the way.
  int back_off_halvings = 4;
  // Then the backed-off vertices with no point within gap_radius take up to settle_rounds
  // steps to their neighbours' mean, each kept only where it crosses nothing: the ragged
  // crease the back-off leaves, smoothed. 0: none. A step shorter than settle_min_step voxels
  // is not taken (a vertex that has settled costs no search).
  int settle_rounds = 16;
  double settle_min_step = 0.05;
  // A cap's solve over at least this many vertices runs its products on the caps' threads (the
  // same bits for any count); a smaller one stays on the calling thread, where an iteration's
  // thread starts would cost more than its products (a 100k-point cloud's caps hold hundreds
  // to thousands of vertices, a 10M-point scan's up to 654k). >= 1.
  int64_t split_solve_vertices = int64_t{1} << 15;
};

struct HoleCapStats {
  int64_t regions = 0;          // gap regions capped
  int64_t vertices = 0;         // vertices of the caps (rims' rings included)
  // Gap regions left: no vertex on the data to hold a cap, more than max_shell_share of
  // their shell, or all of them on data too sparse (min_median_points).
  int64_t uncapped_regions = 0;
  int64_t harmonic_starts = 0;   // caps with no height field: the thin plate from the harmonic map
  int64_t wrapped = 0;           // of those, rims around a swallowed part: thin plate converged
  int64_t swept = 0;             // of those, rims around a post: the cap swept along its axis
  int64_t sphere_converged = 0;  // spline caps converged because the band's sphere says so
  int64_t held_converged = 0;    // caps converged because points seen inside the gap hold them
  int64_t tube_vertices = 0;     // wrapped caps' vertices on thin tubes, solved apart
  int64_t creased = 0;           // caps whose band shows two sides: a crease at a concave corner
  int64_t creased_vertices = 0;  // of their vertices, those moved onto a side's plane
  int64_t iterations = 0;       // conjugate-gradient iterations, every solve
  int64_t anchors = 0;           // cap vertices held at remote points
  int64_t backed_off = 0;       // cap vertices sent back because their faces crossed others
  int64_t settled = 0;          // backed-off vertices moved on by the steps that smooth the crease
  int64_t untangled = 0;         // cap vertices moved to untangle a fold, in regions it untangled
  double max_lift = 0;          // largest move of a vertex by its cap, in voxels
};

// Input: `mesh` closed, manifold, outward and free of self-intersections (SurfaceNets'), in
// model units; `voxel_size` > 0; `points` the input cloud.
// Effect: finds the gap regions (connected sets of vertices with no point within gap_radius,
// each of at least min_gap_vertices, grown by rim_rings rings, each at most max_shell_share of
// its shell; none when the data are sparse, see min_median_points) and spans each with a
// cap. Points seen inside a gap hold it: a cap vertex nearest (within anchor_radius) to points
// with no vertex within gap_radius is held at their mean (anchor_remote_points). The other
// cap vertices are spread by the harmonic map of the region (every other vertex fixed),
// projected on the least-squares plane of the rim samples (the fixed vertices within sample_rings rings)
// and lifted to the thin-plate spline through the samples' heights over that plane (where
// there are too few samples, the rim is no height field (min_rim_cosine) or the spline is
// singular, the harmonic map stays); then thin_plate_iterations conjugate-gradient iterations
// toward the discrete thin plate of the region (the minimum of the sum over vertices of
// |umbrella Laplacian|^2 / degree), or up to wrapped_iterations where the rim is no height
// field and leaves its plane by more than wrap_rms, or where the rim is a height field and the
// band's algebraic sphere prefers the converged plate (sphere_band_fit, sphere_margin), or
// where the cap has held vertices and its rim alone does not make the converged plate bulge
// away from them (converge_held, held_margin); such a cap past coarse_plate_vertices starts
// from the plate of its vertices clustered by cells of a few voxels and takes at most
// coarse_plate_iterations. Regions with no fixed neighbour are left.
// A converged cap whose rim wraps around a post or a thin part's edge is then swept on along
// the part's walls (tube_flatness, tube_lead, swept_length), and so is a spline cap around a
// post, along the post's axis (spline_swept_length), unless points seen inside its gap hold
// it and the swept cap passes farther from them (held_margin). A wrapped cap's vertices on a
// thin tube of the mesh (tube_rings) are solved as their own converging system after the rest
// of it. A cap under the membrane whose band shows two sides meeting at a concave corner is
// creased where their tangent planes meet (corner_angle and the corner_ options). Then it
// searches the faces around moved vertices for crossings: where two faces of the caps cross,
// the fold is untangled by steps to the neighbours' mean (untangle_ options), and a region
// still folded after untangle_rounds goes back to its cap as solved. Then it sends the moved
// vertices of each crossing pair back toward where they were (halfway back_off_halvings
// times, then all the way) until no crossing involves a moved vertex: where a cap would cross
// the mesh, that part of it is not built, and smooths the crease it leaves by settle_rounds
// steps of the backed-off vertices to their neighbours' mean, each kept where it crosses
// nothing.
// Faces are unchanged, so the mesh stays closed, manifold and oriented with its shells and
// genus; crossings are those of the input or none.
// The gap search, the large caps' solves (products and updates; their sums stay in order) and
// every crossing search run on `threads` (<= 1: the calling thread), the rest on the calling
// thread; the result depends only on the input, not on `threads`. `stats` may be null.
// `points_grid`, if not null, is the PointRowGrid of `points` with cells of gap_radius voxels,
// which the gap search and the settling then read instead of building it.
// Errors: InvalidArgument for a bad voxel size or options out of range; Cancelled when
// `cancel` fired (the mesh is then as it came in).
absl::Status CapHoles(TriangleMesh& mesh, double voxel_size, absl::Span<const Point3f> points,
                      const HoleCapOptions& options = {}, HoleCapStats* stats = nullptr,
                      const CancelToken& cancel = CancelToken::Never(), int threads = 1,
                      const PointRowGrid* points_grid = nullptr);

}  // namespace membrane

#endif  // MEMBRANE_CORE_MESH_HOLE_CAPS_H_
