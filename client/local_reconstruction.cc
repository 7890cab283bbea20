#include "client/local_reconstruction.h"

#include <cstdint>
#include <string>
#include <utility>

#include "absl/status/status.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "client/cloud_origin.h"
#include "client/input_files.h"
#include "client/io_errors.h"
#include "core/io/mesh_io.h"
#include "core/pipeline/memory_estimate.h"
#include "core/pipeline/peak_memory.h"
#include "core/pipeline/stopwatch.h"

namespace membrane::client {

absl::Status WithCommandLineContext(const absl::Status& status, const std::string& input) {
  switch (status.code()) {
    case absl::StatusCode::kResourceExhausted:
      return absl::ResourceExhaustedError(absl::StrCat(
          status.message(), "; use a larger --voxel-size or raise --voxel-budget"));
    case absl::StatusCode::kInvalidArgument:
      // Degenerate clouds (no points, all equal, coplanar): name the file they came from.
      return absl::InvalidArgumentError(absl::StrCat(input, ": ", status.message()));
    default: return status;
  }
}

namespace {

// ResourceExhausted when `bytes` are over `limit` (> 0): "<who_needs> about <bytes><purpose>,
// over the memory limit of <limit> (...)<advice>".
absl::Status CheckMemoryLimit(int64_t bytes, int64_t limit, const std::string& who_needs,
                              const char* purpose, const char* advice) {
  if (limit <= 0 || bytes <= limit) return absl::OkStatus();
  return absl::ResourceExhaustedError(absl::StrCat(
      who_needs, " about ", BytesText(bytes), purpose, ", over the memory limit of ",
      BytesText(limit), " (--memory-limit, by default the memory available)", advice));
}

}  // namespace

absl::StatusOr<ReconstructionReport> RunLocalReconstruction(const ReconstructionParams& params,
                                                            const CancelToken& cancel,
                                                            ProgressPrinter& progress) {
  const Stopwatch total;
  const Stopwatch decode;
  progress.Begin(absl::StrCat("decode: reading ", params.input));
  absl::StatusOr<PointCloud> cloud = ReadInputCloud(params.input, cancel);
  if (!cloud.ok()) return FileErrorAsInvalidInput(cloud.status());
  const double decode_seconds = decode.Seconds();
  progress.Finish(absl::StrFormat("decode: %d points%s in %.3f s", cloud->points.size(),
                                  OriginNote(cloud->origin), decode_seconds));
  if (absl::Status s = CheckOutputKeepsOrigin(cloud->origin, params.output); !s.ok()) return s;
  if (cancel.cancelled()) return absl::CancelledError("reconstruction cancelled after decode");

  ReconstructionOptions options = params.options;
  absl::StatusOr<PlannedGrid> plan = PlanGrid(*cloud, options.voxelize);
  if (!plan.ok()) return WithCommandLineContext(plan.status(), params.input);
  options.voxelize.voxel_size = plan->voxel_size;
  const int64_t grid_bytes = plan->bytes;
  if (absl::Status s = CheckMemoryLimit(
          grid_bytes, params.memory_limit_bytes,
          absl::StrFormat("the grid of %d voxels and the %d points need", plan->voxels,
                          cloud->points.size()),
          "", "; use a larger --voxel-size");
      !s.ok())
    return s;
  // Its refusal is the run's status as it is: the voxel-budget advice is not about it.
  absl::Status admission;
  options.admit_surface = [&](const MembraneCounts& membrane) {
    admission = CheckMemoryLimit(
        grid_bytes + SurfaceBytesEstimate(membrane), params.memory_limit_bytes,
        absl::StrFormat("the membrane (%d voxels) needs", membrane.membrane_voxels()),
        " for its surface and the grid",
        "; noise makes a foam of a membrane: is this the scan of one object?");
    return admission;
  };

  // The output is written beside the mesh check (and kept whatever the check finds).
  bool write_failed = false;
  const MeshDelivery write = [&](const TriangleMesh& mesh, const PositionGrid& grid) {
    absl::Status s =
        WriteMesh(mesh, params.output, DracoOptionsOnGrid(grid, params.draco.compression_level));
    write_failed = !s.ok();
    return s;
  };
  absl::StatusOr<ReconstructionResult> result =
      ReconstructCloud(*cloud, options, cancel, progress, write);
  if (!result.ok()) {
    if (write_failed) return FileErrorAsInvalidInput(result.status());
    if (!admission.ok()) return admission;
    return WithCommandLineContext(result.status(), params.input);
  }
  ReconstructionReport& report = result->report;
  report.seconds.decode = decode_seconds;
  report.seconds.total = total.Seconds();
  report.peak_rss_bytes = PeakRssBytes();
  return std::move(report);
}

}  // namespace membrane::client
