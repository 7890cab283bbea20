#include "core/pipeline/decimation_stage.h"

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

#include "absl/status/statusor.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "core/mesh/mesh_decimation.h"
#include "core/mesh/surface_deviation.h"
#include "core/pipeline/stopwatch.h"

namespace membrane {
namespace {

void AddWarning(ReconstructionReport& report, std::string warning) {
  if (std::find(report.warnings.begin(), report.warnings.end(), warning) != report.warnings.end()) {
    return;  // the float32 fallback's second run finds the same
  }
  report.warnings.push_back(std::move(warning));
}

// The collapses' part of the stage's progress; the rest is the deviation's measure (about a
// tenth of the collapses' time on the real clouds' surfaces, tests/bench/2026-12-02-decimate.txt).
constexpr double kCollapsesShare = 0.9;

}  // namespace

absl::Status DecimateStage(const ReconstructionOptions& options, const CancelToken& cancel,
                           const PositionGrid& output_grid, BuiltSurface& surface,
                           ReconstructionReport& report, ReconstructionObserver& observer,
                           ProgressRange progress) {
  if (options.target_faces == 0) return absl::OkStatus();
  const Stopwatch watch;
  observer.StageStarted(PipelineStage::kDecimate, report);
  // The surface as built, to measure what the collapses moved it by.
  const std::vector<Point3f> built = surface.mesh.vertices;
  const int64_t faces_built = static_cast<int64_t>(surface.mesh.faces.size());
  DecimationOptions decimation;
  decimation.target_faces = options.target_faces;
  decimation.grid = output_grid;
  absl::StatusOr<DecimationStats> stats =
      DecimateMesh(surface.mesh, decimation, cancel, progress.Part(0, kCollapsesShare));
  report.decimation = DecimationReport{};
  report.decimation.ran = true;
  if (stats.status().code() == absl::StatusCode::kCancelled || cancel.cancelled()) {
    return absl::CancelledError("reconstruction cancelled after surface");
  }
  if (stats.status().code() == absl::StatusCode::kFailedPrecondition) {
    // The check will say what is wrong with the surface; it is delivered as it is.
    AddWarning(report, absl::StrCat("the mesh was not decimated: ", stats.status().message()));
    report.decimation.stats.target_faces = options.target_faces;
    report.decimation.stats.faces_before = report.decimation.stats.faces_after = faces_built;
    report.decimation.stats.vertices_before = report.decimation.stats.vertices_after =
        static_cast<int64_t>(built.size());
  } else if (!stats.ok()) {
    return stats.status();
  } else {
    report.decimation.stats = *stats;
    if (stats->faces_after != faces_built) {
      surface.crossings.reset();
      report.decimation.error = MeasureDeviation(built, surface.mesh, options.threads, cancel);
      if (cancel.cancelled()) return absl::CancelledError("reconstruction cancelled after surface");
    }
    if (stats->faces_after > options.target_faces) {
      AddWarning(report,
                 absl::StrFormat("the mesh has %d faces, above the target of %d: no further "
                                 "edge collapse keeps it closed, manifold, uncrossed and of the "
                                 "same topology",
                                 stats->faces_after, options.target_faces));
    }
  }
  // The deviation's search counts nothing of its own: the stage is done when it is.
  progress.Part(kCollapsesShare, 1).Done();
  report.mesh.vertices = static_cast<int64_t>(surface.mesh.vertices.size());
  report.mesh.faces = static_cast<int64_t>(surface.mesh.faces.size());
  report.seconds.decimate += watch.Seconds();
  observer.StageFinished(PipelineStage::kDecimate, report.seconds.decimate, report);
  return absl::OkStatus();
}

}  // namespace membrane
