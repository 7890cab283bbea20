#include "core/pipeline/stage_lines.h"

#include <algorithm>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "absl/strings/str_join.h"
#include "core/engine/point_noise.h"

namespace membrane {
namespace {

// What the shrink's passes after the generations changed, each named only when it did
// something: "; 3 pieces of data separated into 3 shells (942 voxels cut, 2 of them hard);
// 1 plugged hole opened; 4702 voxels refilled in data gaps", so that a topology unlike the
// generations' one is explained on the line itself.
std::string PassesAfterGenerations(const ReconstructionReport& r) {
  std::string out;
  if (r.interior_guard.frozen_voxels > 0) {
    absl::StrAppendFormat(&out, "; %d voxels of the interior held by a coarser membrane",
                          r.interior_guard.frozen_voxels);
  }
  const PieceSeparationStats& p = r.piece_separation;
  if (p.separated) {
    absl::StrAppendFormat(&out, "; %d pieces of data separated into %d shells (%d voxels cut",
                          p.pieces, p.shells_after, p.cut_voxels);
    if (p.hard_cut_voxels > 0) absl::StrAppendFormat(&out, ", %d of them hard", p.hard_cut_voxels);
    out += ")";
  } else if (p.pieces >= 2 && p.shells_after > 0) {
    absl::StrAppendFormat(&out, "; %d pieces of data left joined (their cut refused)", p.pieces);
  }
  const HoleOpeningStats& h = r.hole_opening;
  if (h.opened > 0) {
    absl::StrAppendFormat(&out, "; %d plugged hole%s opened", h.opened, h.opened == 1 ? "" : "s");
  }
  if (r.gap_refill.refilled_voxels > 0) {
    absl::StrAppendFormat(&out, "; %d voxels refilled in data gaps", r.gap_refill.refilled_voxels);
  }
  return out;
}

// ", formula (1) L0 raised for the points' noise of S" when the noise chose the voxel size.
std::string NoiseRaisedText(const ReconstructionReport& r) {
  if (!VoxelRaisedForNoise(r.formula_voxel_size, r.voxel_size)) return "";
  return absl::StrFormat(", formula (1)'s %.6g raised for the points' noise of %.3g",
                         r.formula_voxel_size, r.point_noise);
}

}  // namespace

std::string StageStartedLine(PipelineStage stage, const ReconstructionReport& report) {
  switch (stage) {
    case PipelineStage::kShrink:
      return absl::StrFormat("shrink: generation 1/%d ...", report.planned_generations);
    case PipelineStage::kSurface: return absl::StrCat("surface: ", report.surface, " ...");
    default: return absl::StrCat(PipelineStageName(stage), ": ...");
  }
}

std::string GenerationLine(const GenerationStats& g, int planned_generations) {
  return absl::StrFormat(
      "shrink: generation %d/%d, plate size %d: %d soft voxels, %d started contractions, "
      "%d backtrackings, %.3f s%s%s",
      g.generation, planned_generations, g.plate_size, g.soft_voxels, g.started_contractions,
      g.backtrackings, g.seconds,
      g.level > 1 ? absl::StrFormat(" (on the grid %d times coarser)", g.level) : "",
      g.handle_retry ? " (handle retry, kept)" : "");
}

std::string StageFinishedLine(PipelineStage stage, const ReconstructionReport& r) {
  const StageSeconds& s = r.seconds;
  switch (stage) {
    case PipelineStage::kDecode:
      return absl::StrFormat("decode: %d points in %.3f s", r.points, s.decode);
    case PipelineStage::kVoxelize:
      return absl::StrFormat(
          "voxelize: grid %s (voxel size %.6g%s), %d hard voxels, density ratio %.3g in %.3f s",
          absl::StrJoin(r.grid, "x"), r.voxel_size, NoiseRaisedText(r), r.hard_voxels,
          r.density_ratio, s.voxelize);
    case PipelineStage::kShrink:
      return absl::StrFormat(
          "shrink: %d generations in %.3f s; %d of %d inside hard voxels connected to the "
          "membrane%s%s",
          r.generations.size(), s.shrink,
          r.post_process.inside_hard_before - r.post_process.inside_hard_after,
          r.post_process.inside_hard_before,
          r.handle_retry.kept
              ? absl::StrFormat("; handle retry from generation %d: genus %d -> %d",
                                r.handle_retry.from_generation, r.handle_retry.genus_before,
                                r.handle_retry.genus_after)
              : "",
          PassesAfterGenerations(r));
    case PipelineStage::kRelax:
      return absl::StrFormat(
          "relax: %d dents filled, %d bumps shaved, %d steps refused to keep the topology in "
          "%.3f s",
          r.relaxation.phase1_moves, r.relaxation.phase2_moves, r.relaxation.not_simple, s.relax);
    case PipelineStage::kSurface: {
      const QuantizationReport& q = r.quantization;
      std::string grid;
      if (q.bits > 0) {
        grid = absl::StrFormat(
            " on the output's %d-bit grid (step %.3g; each coordinate within %.3g of its float32 "
            "value)",
            q.bits, q.step, q.max_position_error);
      } else if (q.requested_bits > 0) {
        grid = absl::StrFormat(" in float32 (on the %d-bit grid asked for, faces crossed)",
                               q.requested_bits);
      }
      return absl::StrFormat("surface: %s, %d vertices, %d faces%s in %.3f s", r.surface,
                             r.mesh.vertices, r.mesh.faces, grid, s.surface);
    }
    case PipelineStage::kDecimate: {
      const DecimationStats& d = r.decimation.stats;
      return absl::StrFormat(
          "decimate: %d -> %d faces (target %d), %d vertices; the surface moved by at most %.3g, "
          "%.3g on average, in %.3f s",
          d.faces_before, d.faces_after, d.target_faces, d.vertices_after, r.decimation.error.max,
          r.decimation.error.mean, s.decimate);
    }
    case PipelineStage::kCheck: {
      const MeshReport& m = r.mesh;
      return absl::StrFormat(
          "check: %s, %s, %s, %d shell(s), genus [%s], %d self-intersections%s in %.3f s",
          m.closed ? "closed" : "NOT closed", m.manifold ? "manifold" : "NOT manifold",
          m.oriented ? "oriented" : "NOT oriented", m.shells, absl::StrJoin(m.genus, ", "),
          m.self_intersections,
          m.degenerate_faces > 0 ? absl::StrFormat(", %d degenerate faces", m.degenerate_faces)
                                 : "",
          s.check);
    }
    case PipelineStage::kEncode: return absl::StrFormat("encode: done in %.3f s", s.encode);
  }
  return "";
}

std::string ProgressNote(std::optional<double> fraction, double seconds) {
  if (!fraction.has_value()) return absl::StrFormat("%.1f s", seconds);
  const int percent = static_cast<int>(std::clamp(*fraction, 0.0, 1.0) * 100);
  return absl::StrFormat("%d%% in %.1f s", percent, seconds);
}

}  // namespace membrane
