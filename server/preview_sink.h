// The PNG preview of a job's mesh (core/render), drawn as the mesh goes to the job's sink, so
// that it is kept with the result and the web console's job list shows it. The drawing waits
// for the mesh check beside the write to end, and then takes the core the check leaves.
#ifndef MEMBRANE_SERVER_PREVIEW_SINK_H_
#define MEMBRANE_SERVER_PREVIEW_SINK_H_

#include <functional>
#include <optional>
#include <string>

#include "absl/base/thread_annotations.h"
#include "absl/status/statusor.h"
#include "absl/synchronization/mutex.h"
#include "core/base/cancel_token.h"
#include "core/geometry/triangle_mesh.h"
#include "core/pipeline/mesh_sink.h"
#include "core/pipeline/reconstruction_observer.h"

namespace membrane::server {

// The side of each of the preview's three views, in pixels (the picture is 3x as wide).
inline constexpr int kPreviewViewPixels = 160;

// The preview of `mesh`: RenderMeshViews with kPreviewViewPixels views, as PNG. EncodePng's
// errors.
absl::StatusOr<std::string> PreviewPng(const TriangleMesh& mesh);

// A MeshSink that passes the mesh on to `inner` and draws its preview (`draw`, PreviewPng
// unless a test gives another) on a thread beside inner's write, starting when the mesh check
// has ended (CheckEnded), or when the write has, whichever comes first: the check's threads,
// the write and the drawing would otherwise share the cores at once. When no thread can be
// started, the drawing follows the write. The preview is kept only when `inner` took the mesh
// (and not drawn when the write failed before the check ended). Like any sink it only reads
// the mesh.
class PreviewSink : public MeshSink {
 public:
  using Drawing = std::function<absl::StatusOr<std::string>(const TriangleMesh&)>;

  // `inner` and `cancel` (not owned; may be null) must outlive the sink. Once `cancel` fires
  // no drawing starts: the run ends without a result.
  explicit PreviewSink(MeshSink& inner, const CancelToken* cancel = nullptr,
                       Drawing draw = PreviewPng)
      : inner_(inner), cancel_(cancel), draw_(std::move(draw)) {}

  absl::Status CheckOrigin(const Origin3d& origin) override { return inner_.CheckOrigin(origin); }
  // inner's Write, the preview drawn beside it from the check's end; when inner took the mesh,
  // its preview replaces any earlier one. A preview that cannot be drawn leaves none, without
  // failing the run.
  absl::Status Write(const TriangleMesh& mesh, const PositionGrid& grid) override;

  // The check of the next mesh written has started: its drawing waits for CheckEnded (or the
  // write's end). Any thread.
  void CheckStarted();
  // The check of the mesh being written (or about to be) has ended: its drawing may start.
  // Any thread.
  void CheckEnded();

  // The PNG of the last mesh written; empty when none.
  std::string TakePng() { return std::move(png_); }

 private:
  MeshSink& inner_;
  const CancelToken* cancel_;
  Drawing draw_;
  std::string png_;
  absl::Mutex mutex_;
  bool check_ended_ ABSL_GUARDED_BY(mutex_) = false;
  // Of the Write running: nullopt until inner's write returns, then whether it took the mesh.
  std::optional<bool> written_ ABSL_GUARDED_BY(mutex_);
};

// A ReconstructionObserver that passes every call on to `inner` and tells `preview` when the
// mesh check starts (StageStarted) and when its progress says all its work is done
// (StageProgress of the check at 1, from the run's progress thread on inner's schedule: a
// second at most after the check's end with the job's observer). Both must outlive it.
class PreviewCheckObserver : public ReconstructionObserver {
 public:
  PreviewCheckObserver(ReconstructionObserver& inner, PreviewSink& preview)
      : inner_(inner), preview_(preview) {}

  std::optional<ProgressSchedule> progress_schedule() const override {
    return inner_.progress_schedule();
  }
  void StageProgress(PipelineStage stage, std::optional<double> fraction,
                     double seconds) override;
  void StageStarted(PipelineStage stage, const ReconstructionReport& report) override;
  void GenerationFinished(const GenerationStats& generation, int planned_generations) override {
    inner_.GenerationFinished(generation, planned_generations);
  }
  void StageFinished(PipelineStage stage, double seconds,
                     const ReconstructionReport& report) override {
    inner_.StageFinished(stage, seconds, report);
  }

 private:
  ReconstructionObserver& inner_;
  PreviewSink& preview_;
};

}  // namespace membrane::server

#endif  // MEMBRANE_SERVER_PREVIEW_SINK_H_
