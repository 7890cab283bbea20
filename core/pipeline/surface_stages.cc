#include "core/pipeline/surface_stages.h"

#include <cstdint>
#include <string>
#include <system_error>
#include <thread>
#include <utility>

#include "absl/strings/str_format.h"
#include "core/engine/point_noise.h"
#include "core/mesh/mesh_check.h"
#include "core/pipeline/stopwatch.h"

namespace membrane {

absl::StatusOr<BuiltSurface> SurfaceStage(const ReconstructionOptions& options,
                                          const CancelToken& cancel, VoxelGrid&& grid,
                                          const PointCloud& cloud,
                                          const PositionGrid& output_grid,
                                          ReconstructionReport& report,
                                          ReconstructionObserver& observer, double point_noise,
                                          ProgressRange progress) {
  const Stopwatch watch;
  observer.StageStarted(PipelineStage::kSurface, report);
  absl::StatusOr<BuiltSurface> built = BuildSurface(std::move(grid), cloud, options.surface,
                                                    output_grid, cancel, options.threads,
                                                    progress, point_noise);
  if (!built.ok()) return built.status();
  report.hole_caps = built->hole_caps;
  report.fit = built->fit;
  report.surface_seconds = built->steps;
  report.quantization.bits = output_grid.bits;
  report.quantization.step = output_grid.step();
  report.quantization.max_position_error = output_grid.step() / 2;
  report.seconds.surface += watch.Seconds();
  // Known now; the check repeats them with the rest of its findings.
  report.mesh.vertices = static_cast<int64_t>(built->mesh.vertices.size());
  report.mesh.faces = static_cast<int64_t>(built->mesh.faces.size());
  observer.StageFinished(PipelineStage::kSurface, report.seconds.surface, report);
  return built;
}

// Why a cloud gave no surface at all: at this voxel size its points are too few, or too far
// apart, to hold the membrane (a handful of points, or a stray point far away that stretches
// the box and so the formula-(1) voxel size). An empty mesh is no answer: say so.
// When the points' noise chose that size, the noise is named too: points spread through a
// volume read as noise several formula-(1) voxels deep.
absl::Status EmptySurfaceError(const ReconstructionReport& report) {
  const std::string noise =
      VoxelRaisedForNoise(report.formula_voxel_size, report.voxel_size)
          ? absl::StrFormat(
                " (the size of the points' scatter across their surface, %g, where formula "
                "(1) gives %g: do they sample a surface?)",
                report.point_noise, report.formula_voxel_size)
          : "";
  return absl::InvalidArgumentError(absl::StrFormat(
      "no surface: at voxel size %g%s (a %dx%dx%d grid) the %d points fill only %d voxel%s, too "
      "few to enclose a solid; give a denser cloud, remove stray points far from the object, "
      "or ask for a smaller voxel size",
      report.voxel_size, noise, report.data_grid[0], report.data_grid[1], report.data_grid[2],
      report.points, report.hard_voxels, report.hard_voxels == 1 ? "" : "s"));
}

// The check has its own thread, so that the sink, which encodes, allocates from the calling
// thread's malloc arena, whose pages earlier stages have already faulted in (a fresh arena
// made Draco's encode twice as slow, most of it in page faults).
// Crossings the surface step already searched for are taken, not searched again: the smooth
// surface's fit ends with a search of the whole mesh on its final positions, and repeating it
// would be most of the check (tests/bench/2026-12-01-surface-threads.txt). Where the check
// does search (cuberille), the search gets all `threads`: it is longer than the encode (0.1 s
// against 0.03 s on a mesh of fandisk-variable's size), and leaving the encode a core of its
// own would leave that core idle once the encode is done.
absl::Status CheckAndWriteStage(const BuiltSurface& surface, const PositionGrid& grid,
                                int threads, const CancelToken& cancel, MeshSink& sink,
                                ReconstructionReport& report, ReconstructionObserver& observer,
                                ProgressRange progress) {
  observer.StageStarted(PipelineStage::kCheck, report);
  MeshReport checked;
  double check_seconds = 0;
  auto check = [&] {
    const Stopwatch watch;
    checked = CheckMesh(surface.mesh, cancel, threads,
                        surface.crossings ? &*surface.crossings : nullptr, progress);
    check_seconds = watch.Seconds();
  };
  // Out of threads, the check runs after the write instead of beside it.
  std::thread checker;
  try {
    checker = std::thread(check);
  } catch (const std::system_error&) {
  }
  const Stopwatch write_watch;
  const absl::Status written = sink.Write(surface.mesh, grid);
  const double write_seconds = write_watch.Seconds();
  if (checker.joinable()) {
    checker.join();
  } else {
    check();
  }
  report.mesh = checked;
  report.seconds.check += check_seconds;
  observer.StageFinished(PipelineStage::kCheck, check_seconds, report);
  observer.StageStarted(PipelineStage::kEncode, report);
  report.seconds.encode += write_seconds;
  observer.StageFinished(PipelineStage::kEncode, write_seconds, report);
  return written;
}

}  // namespace membrane
