#include "server/preview_sink.h"

#include <system_error>
#include <thread>
#include <utility>

#include "core/render/mesh_views.h"
#include "core/render/png_codec.h"

namespace membrane::server {

absl::StatusOr<std::string> PreviewPng(const TriangleMesh& mesh) {
  MeshViewOptions options;
  options.view_pixels = kPreviewViewPixels;
  return EncodePng(RenderMeshViews(mesh, options));
}

// Draco's encoder is serial, and on a big mesh it outlasts the check beside it: the drawing
// fits in the core the check leaves. Drawn at once, it shares the cores with both (the
// 10M-point torus's check longer: tests/bench/2026-12-06-server-encode.txt).
absl::Status PreviewSink::Write(const TriangleMesh& mesh, const PositionGrid& grid) {
  {
    absl::MutexLock lock(&mutex_);
    written_.reset();
  }
  absl::StatusOr<std::string> png = std::string();
  const auto draw = [&] {
    {
      absl::MutexLock lock(&mutex_);
      const auto may_draw = [this]() ABSL_EXCLUSIVE_LOCKS_REQUIRED(mutex_) {
        return check_ended_ || written_.has_value();
      };
      mutex_.Await(absl::Condition(&may_draw));
      if (written_.has_value() && !*written_) return;  // no mesh taken, no preview kept
    }
    // The run ends with the token's status after the write: no preview is kept.
    if (cancel_ != nullptr && cancel_->cancelled()) return;
    png = draw_(mesh);
  };
  std::thread drawer;
  try {
    drawer = std::thread(draw);
  } catch (const std::system_error&) {
  }
  const absl::Status written = inner_.Write(mesh, grid);
  {
    absl::MutexLock lock(&mutex_);
    written_ = written.ok();
  }
  if (drawer.joinable()) {
    drawer.join();
  } else {
    draw();
  }
  if (!written.ok()) return written;
  png_ = png.ok() ? *std::move(png) : std::string();
  return absl::OkStatus();
}

void PreviewSink::CheckStarted() {
  absl::MutexLock lock(&mutex_);
  check_ended_ = false;
}

void PreviewSink::CheckEnded() {
  absl::MutexLock lock(&mutex_);
  check_ended_ = true;
}

void PreviewCheckObserver::StageProgress(PipelineStage stage, std::optional<double> fraction,
                                         double seconds) {
  if (stage == PipelineStage::kCheck && fraction.has_value() && *fraction >= 1) {
    preview_.CheckEnded();
  }
  inner_.StageProgress(stage, fraction, seconds);
}

void PreviewCheckObserver::StageStarted(PipelineStage stage, const ReconstructionReport& report) {
  if (stage == PipelineStage::kCheck) preview_.CheckStarted();
  inner_.StageStarted(stage, report);
}

}  // namespace membrane::server
