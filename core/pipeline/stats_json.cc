#include "core/pipeline/stats_json.h"

#include <string>
#include <vector>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "absl/strings/str_join.h"
#include "core/pipeline/json_text.h"

namespace membrane {
namespace {

std::string IntArray(const auto& values) {
  return absl::StrCat("[", absl::StrJoin(values, ", "), "]");
}

std::string GenerationJson(const GenerationStats& g) {
  return absl::StrCat("{\"plate_size\": ", g.plate_size, ", \"soft_voxels\": ", g.soft_voxels,
                      ", \"started_contractions\": ", g.started_contractions,
                      ", \"backtrackings\": ", g.backtrackings,
                      ", \"seconds\": ", JsonNumber(g.seconds), ", \"generation\": ", g.generation,
                      ", \"contractions\": ", g.contractions,
                      ", \"undone_contractions\": ", g.undone_contractions,
                      ", \"guard_refusals\": ", g.guard_refusals,
                      ", \"depth_refusals\": ", g.depth_refusals, ", \"passes\": ", g.passes,
                      ", \"local_passes\": ", g.local_passes, ", \"level\": ", g.level, "}");
}

std::string GenerationsJson(const std::vector<GenerationStats>& generations) {
  std::vector<std::string> rows;
  rows.reserve(generations.size());
  for (const GenerationStats& g : generations) rows.push_back(GenerationJson(g));
  if (rows.empty()) return "[]";
  return absl::StrCat("[\n    ", absl::StrJoin(rows, ",\n    "), "\n  ]");
}

std::string PostProcessJson(const PostProcessStats& p) {
  return absl::StrCat("{\"inside_hard_before\": ", p.inside_hard_before,
                      ", \"inside_hard_after\": ", p.inside_hard_after,
                      ", \"carved_voxels\": ", p.carved_voxels,
                      ", \"bridge_voxels\": ", p.bridge_voxels,
                      ", \"seconds\": ", JsonNumber(p.seconds), "}");
}

std::string HandleRetryJson(const HandleRetry& h) {
  return absl::StrCat("{\"ran\": ", JsonBool(h.ran), ", \"kept\": ", JsonBool(h.kept),
                      ", \"from_generation\": ", h.from_generation,
                      ", \"loose_tunnels\": ", h.loose_tunnels,
                      ", \"shells_before\": ", h.shells_before,
                      ", \"genus_before\": ", h.genus_before,
                      ", \"shells_after\": ", h.shells_after, ", \"genus_after\": ", h.genus_after,
                      ", \"web_voxels\": ", h.web_voxels,
                      ", \"web_hard_rim\": ", JsonNumber(h.web_hard_rim),
                      ", \"seconds\": ", JsonNumber(h.seconds), "}");
}

std::string PieceSeparationJson(const PieceSeparationStats& p) {
  return absl::StrCat("{\"pieces\": ", p.pieces, ", \"separated\": ", JsonBool(p.separated),
                      ", \"cut_voxels\": ", p.cut_voxels,
                      ", \"hard_cut_voxels\": ", p.hard_cut_voxels,
                      ", \"web_voxels\": ", p.web_voxels,
                      ", \"loops_closed\": ", p.loops_closed,
                      ", \"far_steps_cut\": ", p.far_steps_cut,
                      ", \"shells_before\": ", p.shells_before,
                      ", \"genus_before\": ", p.genus_before,
                      ", \"shells_after\": ", p.shells_after, ", \"genus_after\": ", p.genus_after,
                      ", \"cavities_after\": ", p.cavities_after,
                      ", \"cut_fraction\": ", JsonNumber(p.cut_fraction),
                      ", \"seconds\": ", JsonNumber(p.seconds), "}");
}

std::string HoleOpeningJson(const HoleOpeningStats& h) {
  return absl::StrCat("{\"opened\": ", h.opened, ", \"refused\": ", h.refused,
                      ", \"wall_core_kept\": ", h.wall_cores,
                      ", \"carved_voxels\": ", h.carved_voxels,
                      ", \"whole_grid_counts\": ", h.whole_grid_counts,
                      ", \"seconds\": ", JsonNumber(h.seconds), "}");
}

std::string GapRefillJson(const GapRefillStats& g) {
  return absl::StrCat("{\"refilled_voxels\": ", g.refilled_voxels,
                      ", \"pocket_voxels\": ", g.pocket_voxels,
                      ", \"loops_closed\": ", g.loops_closed,
                      ", \"seconds\": ", JsonNumber(g.seconds), "}");
}

std::string InteriorGuardJson(const InteriorGuardStats& g) {
  return absl::StrCat("{\"levels\": ", g.levels, ", \"core_voxels\": ", g.core_voxels,
                      ", \"frozen_voxels\": ", g.frozen_voxels,
                      ", \"band_frozen\": ", g.band_frozen,
                      ", \"released_voxels\": ", g.released_voxels,
                      ", \"seconds\": ", JsonNumber(g.seconds), "}");
}

std::string CoarsePlatesJson(const CoarsePlatesStats& c) {
  return absl::StrCat("{\"factor\": ", c.factor, ", \"generations\": ", c.generations,
                      ", \"lifted_voxels\": ", c.lifted_voxels,
                      ", \"seconds\": ", JsonNumber(c.seconds), "}");
}

std::string TopologyGuardJson(const GuardSizes& g) {
  return absl::StrCat("{\"tunnel_min_plate\": ", g.tunnel_min_plate,
                      ", \"object_tunnel_plate\": ", g.object_tunnel_plate,
                      ", \"dense_rim\": ", JsonNumber(g.dense_rim), "}");
}

std::string RelaxationJson(const RelaxationStats& r) {
  return absl::StrCat("{\"phase1_moves\": ", r.phase1_moves, ", \"phase1_added\": ", r.phase1_added,
                      ", \"phase2_moves\": ", r.phase2_moves,
                      ", \"phase2_uncovered\": ", r.phase2_uncovered,
                      ", \"not_simple\": ", r.not_simple, "}");
}

std::string MembraneJson(const MembraneCounts& m) {
  return absl::StrCat(
      "{\"hard_voxels\": ", m.hard_voxels, ", \"frozen_voxels\": ", m.frozen_voxels,
      ", \"soft_voxels\": ", m.soft_voxels, ", \"inside_hard_voxels\": ", m.inside_hard_voxels,
      ", \"inside_soft_voxels\": ", m.inside_soft_voxels, ", \"shells\": ", m.shells,
      ", \"inside_frozen_voxels\": ", m.inside_frozen_voxels, ", \"genus\": ", IntArray(m.genus),
      "}");
}

std::string MeshJson(const MeshReport& m) {
  return absl::StrCat(
      "{\"vertices\": ", m.vertices, ", \"faces\": ", m.faces, ", \"closed\": ", JsonBool(m.closed),
      ", \"manifold\": ", JsonBool(m.manifold), ", \"oriented\": ", JsonBool(m.oriented),
      ", \"shells\": ", m.shells, ", \"genus\": ", IntArray(m.genus),
      ", \"self_intersections\": ", m.self_intersections,
      ", \"positive_volume\": ", JsonBool(m.positive_volume),
      ", \"degenerate_faces\": ", m.degenerate_faces, "}");
}

std::string HoleCapsJson(const HoleCapStats& h) {
  return absl::StrCat("{\"regions\": ", h.regions, ", \"vertices\": ", h.vertices,
                      ", \"harmonic_starts\": ", h.harmonic_starts,
                      ", \"wrapped_caps\": ", h.wrapped,
                      ", \"swept_caps\": ", h.swept,
                      ", \"sphere_converged_caps\": ", h.sphere_converged,
                      ", \"held_converged_caps\": ", h.held_converged,
                      ", \"tube_vertices\": ", h.tube_vertices,
                      ", \"creased_caps\": ", h.creased,
                      ", \"creased_vertices\": ", h.creased_vertices,
                      ", \"uncapped_regions\": ", h.uncapped_regions,
                      ", \"anchored_vertices\": ", h.anchors,
                      ", \"untangled_vertices\": ", h.untangled,
                      ", \"backed_off_vertices\": ", h.backed_off,
                      ", \"settled_vertices\": ", h.settled,
                      ", \"max_lift_voxels\": ", JsonNumber(h.max_lift), "}");
}

std::string FitJson(const FitTargetCounts& f) {
  return absl::StrCat("{\"quadric_targets\": ", f.quadric, ", \"plane_targets\": ", f.plane,
                      ", \"crease_targets\": ", f.crease,
                      ", \"crease_line_targets\": ", f.crease_line,
                      ", \"umbrella_targets\": ", f.umbrella, "}");
}

std::string SecondsJson(const StageSeconds& s) {
  return absl::StrCat(
      "{\"decode\": ", JsonNumber(s.decode), ", \"voxelize\": ", JsonNumber(s.voxelize),
      ", \"shrink\": ", JsonNumber(s.shrink), ", \"relax\": ", JsonNumber(s.relax),
      ", \"surface\": ", JsonNumber(s.surface), ", \"decimate\": ", JsonNumber(s.decimate),
      ", \"encode\": ", JsonNumber(s.encode),
      ", \"total\": ", JsonNumber(s.total), ", \"check\": ", JsonNumber(s.check), "}");
}

std::string SurfaceSecondsJson(const SurfaceStepSeconds& s) {
  return absl::StrCat("{\"prepare\": ", JsonNumber(s.prepare), ", \"nets\": ", JsonNumber(s.nets),
                      ", \"caps\": ", JsonNumber(s.caps), ", \"fit\": ", JsonNumber(s.fit), "}");
}

// Whole units up to 2^40 (CoordinateShift): %.17g prints them exactly, where JsonNumber's 9
// digits would not.
std::string OriginJson(const std::array<double, 3>& o) {
  return absl::StrFormat("[%.17g, %.17g, %.17g]", o[0], o[1], o[2]);
}

std::string QuantizationJson(const QuantizationReport& q) {
  return absl::StrCat("{\"requested_bits\": ", q.requested_bits, ", \"bits\": ", q.bits,
                      ", \"step\": ", JsonNumber(q.step),
                      ", \"max_position_error\": ", JsonNumber(q.max_position_error), "}");
}

// null without a face budget.
std::string DecimationJson(const DecimationReport& d) {
  if (!d.ran) return "null";
  const DecimationStats& s = d.stats;
  return absl::StrCat("{\"target_faces\": ", s.target_faces, ", \"faces_before\": ", s.faces_before,
                      ", \"faces_after\": ", s.faces_after,
                      ", \"vertices_before\": ", s.vertices_before,
                      ", \"vertices_after\": ", s.vertices_after, ", \"collapses\": ", s.collapses,
                      ", \"refused_collapses\": ", s.refused, ", \"passes\": ", s.passes,
                      ", \"max_error\": ", JsonNumber(d.error.max),
                      ", \"mean_error\": ", JsonNumber(d.error.mean), "}");
}

std::string WarningsJson(const std::vector<std::string>& warnings) {
  std::string out = "[";
  for (size_t i = 0; i < warnings.size(); ++i)
    absl::StrAppend(&out, i > 0 ? ", " : "", JsonString(warnings[i]));
  return out + "]";
}

}  // namespace

std::string StatsJson(const ReconstructionReport& r) {
  return absl::StrCat(
      "{\n  \"points\": ", r.points, ",\n  \"voxel_size\": ", JsonNumber(r.voxel_size),
      ",\n  \"formula_voxel_size\": ", JsonNumber(r.formula_voxel_size),
      ",\n  \"point_noise\": ", JsonNumber(r.point_noise),
      ",\n  \"grid\": ", IntArray(r.grid), ",\n  \"hard_voxels\": ", r.hard_voxels,
      ",\n  \"density_ratio\": ", JsonNumber(r.density_ratio),
      ",\n  \"generations\": ", GenerationsJson(r.generations),
      ",\n  \"membrane\": ", MembraneJson(r.membrane), ",\n  \"mesh\": ", MeshJson(r.mesh),
      ",\n  \"seconds\": ", SecondsJson(r.seconds),
      ",\n  \"surface_seconds\": ", SurfaceSecondsJson(r.surface_seconds),
      ",\n  \"peak_rss_bytes\": ", r.peak_rss_bytes,
      ",\n  \"data_grid\": ", IntArray(r.data_grid), ",\n  \"schedule\": ", JsonString(r.schedule),
      ",\n  \"surface\": ", JsonString(r.surface), ",\n  \"relaxed\": ", JsonBool(r.relaxed),
      ",\n  \"threads\": ", r.threads,
      ",\n  \"post_process\": ", PostProcessJson(r.post_process),
      ",\n  \"handle_retry\": ", HandleRetryJson(r.handle_retry),
      ",\n  \"piece_separation\": ", PieceSeparationJson(r.piece_separation),
      ",\n  \"hole_opening\": ", HoleOpeningJson(r.hole_opening),
      ",\n  \"gap_refill\": ", GapRefillJson(r.gap_refill),
      ",\n  \"interior_guard\": ", InteriorGuardJson(r.interior_guard),
      ",\n  \"coarse_plates\": ", CoarsePlatesJson(r.coarse_plates),
      ",\n  \"topology_guard\": ", TopologyGuardJson(r.topology_guard),
      ",\n  \"relaxation\": ", RelaxationJson(r.relaxation),
      ",\n  \"hole_caps\": ", HoleCapsJson(r.hole_caps),
      ",\n  \"fit\": ", FitJson(r.fit),
      ",\n  \"quantization\": ", QuantizationJson(r.quantization),
      ",\n  \"decimation\": ", DecimationJson(r.decimation),
      ",\n  \"origin\": ", OriginJson(r.origin),
      ",\n  \"warnings\": ", WarningsJson(r.warnings), "\n}\n");
}

}  // namespace membrane
