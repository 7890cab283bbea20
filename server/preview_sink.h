// The PNG preview of a job's mesh (core/render), drawn as the mesh goes to the job's sink, so
// that it is kept with the result and the web console's job list shows it.
#ifndef MEMBRANE_SERVER_PREVIEW_SINK_H_
#define MEMBRANE_SERVER_PREVIEW_SINK_H_

#include <string>

#include "absl/status/statusor.h"
#include "core/geometry/triangle_mesh.h"
#include "core/pipeline/mesh_sink.h"

namespace membrane::server {

// The side of each of the preview's three views, in pixels (the picture is 3x as wide).
inline constexpr int kPreviewViewPixels = 160;

// The preview of `mesh`: RenderMeshViews with kPreviewViewPixels views, as PNG. EncodePng's
// errors.
absl::StatusOr<std::string> PreviewPng(const TriangleMesh& mesh);

// A MeshSink that passes the mesh on to `inner` and draws its preview (PreviewPng) on a thread
// beside inner's write (after it when no thread can be started). The preview is kept only when
// `inner` took the mesh. Like any sink it only reads the mesh.
class PreviewSink : public MeshSink {
 public:
  // `inner` (not owned) must outlive the sink.
  explicit PreviewSink(MeshSink& inner) : inner_(inner) {}

  absl::Status CheckOrigin(const Origin3d& origin) override { return inner_.CheckOrigin(origin); }
  // inner's Write, the preview drawn beside it; when inner took the mesh, its preview replaces
  // any earlier one. A preview that cannot be drawn leaves none, without failing the run.
  absl::Status Write(const TriangleMesh& mesh, const PositionGrid& grid) override;

  // The PNG of the last mesh written; empty when none.
  std::string TakePng() { return std::move(png_); }

 private:
  MeshSink& inner_;
  std::string png_;
};

}  // namespace membrane::server

#endif  // MEMBRANE_SERVER_PREVIEW_SINK_H_
