#include "client/local_reconstruction.h"

#include <utility>

#include "absl/status/status.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "client/cloud_origin.h"
#include "client/input_files.h"
#include "client/io_errors.h"
#include "core/io/mesh_io.h"
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

  // The output is written beside the mesh check (and kept whatever the check finds).
  bool write_failed = false;
  const MeshDelivery write = [&](const TriangleMesh& mesh, const PositionGrid& grid) {
    absl::Status s =
        WriteMesh(mesh, params.output, DracoOptionsOnGrid(grid, params.draco.compression_level));
    write_failed = !s.ok();
    return s;
  };
  absl::StatusOr<ReconstructionResult> result =
      ReconstructCloud(*cloud, params.options, cancel, progress, write);
  if (!result.ok()) {
    if (write_failed) return FileErrorAsInvalidInput(result.status());
    return WithCommandLineContext(result.status(), params.input);
  }
  ReconstructionReport& report = result->report;
  report.seconds.decode = decode_seconds;
  report.seconds.total = total.Seconds();
  report.peak_rss_bytes = PeakRssBytes();
  return std::move(report);
}

}  // namespace membrane::client
