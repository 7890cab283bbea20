// PreviewSink (server/preview_sink.h): the preview is drawn beside the inner sink's write once
// the mesh check has ended (or after the write when it ends first), and kept only when the
// inner sink took the mesh. PreviewCheckObserver tells the sink when the check ends.
#include "server/preview_sink.h"

#include <algorithm>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "absl/base/thread_annotations.h"
#include "absl/status/status.h"
#include "absl/synchronization/mutex.h"
#include "absl/time/time.h"
#include "core/base/cancel_token.h"
#include "core/geometry/position_grid.h"
#include "core/pipeline/draco_mesh_sink.h"
#include "tests/mesh/mesh_builders.h"

namespace membrane::server {
namespace {

// A sink that counts the faces it was given and answers with `status`.
class CountingSink : public MeshSink {
 public:
  explicit CountingSink(absl::Status status) : status_(std::move(status)) {}
  absl::Status Write(const TriangleMesh& mesh, const PositionGrid& /*grid*/) override {
    faces_ += mesh.faces.size();
    return status_;
  }
  size_t faces() const { return faces_; }

 private:
  absl::Status status_;
  size_t faces_ = 0;
};

// What happened, in order, from any thread; a wait for an entry (no sleeping).
class Log {
 public:
  void Add(const std::string& entry) {
    absl::MutexLock lock(&mutex_);
    entries_.push_back(entry);
  }
  // Whether `entry` was logged within a minute (a drawing that never starts fails the test
  // instead of hanging it).
  bool WaitFor(const std::string& entry) {
    const auto logged = [this, &entry]() ABSL_NO_THREAD_SAFETY_ANALYSIS {
      return std::find(entries_.begin(), entries_.end(), entry) != entries_.end();
    };
    absl::MutexLock lock(&mutex_);
    return mutex_.AwaitWithTimeout(absl::Condition(&logged), absl::Minutes(1));
  }
  std::vector<std::string> entries() {
    absl::MutexLock lock(&mutex_);
    return entries_;
  }

 private:
  absl::Mutex mutex_;
  std::vector<std::string> entries_ ABSL_GUARDED_BY(mutex_);
};

// A drawing that logs when it starts and draws the real preview.
PreviewSink::Drawing LoggedDrawing(Log& log) {
  return [&log](const TriangleMesh& mesh) {
    log.Add("drawing");
    return PreviewPng(mesh);
  };
}

// An inner sink that encodes the mesh as the job's does (Draco, a tenth of a second or so on
// BigTorus: a drawing that started at once would be logged during it), then runs `during`, and
// answers with `status`.
class LoggedSink : public MeshSink {
 public:
  LoggedSink(Log& log, std::function<void()> during, absl::Status status = absl::OkStatus())
      : log_(log), during_(std::move(during)), status_(std::move(status)) {}
  absl::Status Write(const TriangleMesh& mesh, const PositionGrid& grid) override {
    log_.Add("write starts");
    EXPECT_TRUE(draco_.Write(mesh, grid).ok());
    if (during_) during_();
    log_.Add("write ends");
    return status_;
  }

 private:
  Log& log_;
  std::function<void()> during_;
  absl::Status status_;
  DracoMeshSink draco_{7};
};

// 230k faces.
TriangleMesh BigTorus() { return testing::TorusMesh(480, 240, 1.0f, 0.3f); }

TEST(PreviewSink, KeepsAPictureOfTheMeshTheInnerSinkTook) {
  const TriangleMesh torus = testing::TorusMesh(48, 24, 1.0f, 0.3f);
  CountingSink inner(absl::OkStatus());
  PreviewSink sink(inner);
  ASSERT_TRUE(sink.Write(torus, BoundingGrid(torus.vertices, 16)).ok());
  EXPECT_EQ(inner.faces(), torus.faces.size());
  const std::string png = sink.TakePng();
  ASSERT_FALSE(png.empty());
  EXPECT_EQ(png.substr(1, 3), "PNG");
  const absl::StatusOr<std::string> alone = PreviewPng(torus);
  ASSERT_TRUE(alone.ok()) << alone.status();
  EXPECT_EQ(png, *alone);  // the same picture as drawn on the calling thread
}

TEST(PreviewSink, ReturnsTheInnerSinksErrorAndDrawsNoPicture) {
  const TriangleMesh torus = BigTorus();
  Log log;
  LoggedSink inner(log, nullptr, absl::ResourceExhaustedError("the mesh is over the result limit"));
  PreviewSink sink(inner, nullptr, LoggedDrawing(log));
  sink.CheckStarted();
  const absl::Status written = sink.Write(torus, BoundingGrid(torus.vertices, 16));
  EXPECT_EQ(written.code(), absl::StatusCode::kResourceExhausted);
  EXPECT_EQ(written.message(), "the mesh is over the result limit");
  EXPECT_TRUE(sink.TakePng().empty());
  // The check never ended, and the write failed: nothing drawn.
  EXPECT_EQ(log.entries(), (std::vector<std::string>{"write starts", "write ends"}));
}

// The order of a job: the check starts, the write starts beside it, the check ends (its
// progress at 1, through the observer), and the drawing starts then, while the write goes on.
TEST(PreviewSink, DrawsBesideTheWriteOnceTheCheckHasEnded) {
  const TriangleMesh torus = BigTorus();
  Log log;
  NullReconstructionObserver events;
  PreviewCheckObserver* observer = nullptr;  // set below: the sink comes first
  LoggedSink inner(log, [&] {
    observer->StageProgress(PipelineStage::kCheck, 0.5, 1.0);
    log.Add("check half done");
    observer->StageProgress(PipelineStage::kSurface, 1.0, 1.0);  // not the check's end
    log.Add("check ends");
    observer->StageProgress(PipelineStage::kCheck, 1.0, 2.0);
    EXPECT_TRUE(log.WaitFor("drawing"));
  });
  PreviewSink sink(inner, nullptr, LoggedDrawing(log));
  PreviewCheckObserver check_observer(events, sink);
  observer = &check_observer;
  ReconstructionReport report;
  check_observer.StageStarted(PipelineStage::kCheck, report);
  ASSERT_TRUE(sink.Write(torus, BoundingGrid(torus.vertices, 16)).ok());
  EXPECT_EQ(log.entries(), (std::vector<std::string>{"write starts", "check half done",
                                                     "check ends", "drawing", "write ends"}));
  const absl::StatusOr<std::string> alone = PreviewPng(torus);
  ASSERT_TRUE(alone.ok()) << alone.status();
  EXPECT_EQ(sink.TakePng(), *alone);
}

// A check that has not ended when the write does (a cancelled or uncounted check, a run
// without progress) leaves the drawing after the write; a check's end from before the next
// check started counts nothing (the float32 fallback writes a second mesh).
TEST(PreviewSink, DrawsAfterTheWriteWhenTheCheckHasNotEnded) {
  const TriangleMesh torus = BigTorus();
  Log log;
  LoggedSink inner(log, nullptr);
  PreviewSink sink(inner, nullptr, LoggedDrawing(log));
  sink.CheckEnded();  // the first mesh's check
  sink.CheckStarted();
  ASSERT_TRUE(sink.Write(torus, BoundingGrid(torus.vertices, 16)).ok());
  EXPECT_EQ(log.entries(), (std::vector<std::string>{"write starts", "write ends", "drawing"}));
  EXPECT_FALSE(sink.TakePng().empty());
}

// A job cancelled during the write ends without a result once the write returns: the drawing
// does not start, even when the check then reports its end.
TEST(PreviewSink, DrawsNothingOnceTheRunIsCancelled) {
  const TriangleMesh torus = BigTorus();
  Log log;
  CancelToken cancel;
  PreviewSink* preview = nullptr;  // set below: the inner sink comes first
  LoggedSink inner(log, [&] {
    cancel.Cancel();
    preview->CheckEnded();
  });
  PreviewSink sink(inner, &cancel, LoggedDrawing(log));
  preview = &sink;
  sink.CheckStarted();
  ASSERT_TRUE(sink.Write(torus, BoundingGrid(torus.vertices, 16)).ok());
  EXPECT_EQ(log.entries(), (std::vector<std::string>{"write starts", "write ends"}));
  EXPECT_TRUE(sink.TakePng().empty());
}

}  // namespace
}  // namespace membrane::server
