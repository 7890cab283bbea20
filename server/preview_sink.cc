#include "server/preview_sink.h"

#include <utility>

#include "core/render/mesh_views.h"
#include "core/render/png_codec.h"

namespace membrane::server {

absl::StatusOr<std::string> PreviewPng(const TriangleMesh& mesh) {
  MeshViewOptions options;
  options.view_pixels = kPreviewViewPixels;
  return EncodePng(RenderMeshViews(mesh, options));
}

absl::Status PreviewSink::Write(const TriangleMesh& mesh, const PositionGrid& grid) {
  if (absl::Status s = inner_.Write(mesh, grid); !s.ok()) return s;
  absl::StatusOr<std::string> png = PreviewPng(mesh);
  png_ = png.ok() ? *std::move(png) : std::string();
  return absl::OkStatus();
}

}  // namespace membrane::server
