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

absl::Status PreviewSink::Write(const TriangleMesh& mesh, const PositionGrid& grid) {
  // The drawing runs beside the inner write (Draco's encoder is serial: a big mesh's encode
  // outlasts the check beside it and leaves a core free); out of threads, after it.
  absl::StatusOr<std::string> png = std::string();
  const auto draw = [&] { png = PreviewPng(mesh); };
  std::thread drawer;
  try {
    drawer = std::thread(draw);
  } catch (const std::system_error&) {
  }
  const absl::Status written = inner_.Write(mesh, grid);
  if (drawer.joinable()) {
    drawer.join();
  } else if (written.ok()) {
    draw();
  }
  if (!written.ok()) return written;
  png_ = png.ok() ? *std::move(png) : std::string();
  return absl::OkStatus();
}

}  // namespace membrane::server
