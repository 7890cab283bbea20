#include "client/render_command.h"

#include <memory>
#include <string>

#include "CLI/CLI.hpp"
#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "absl/strings/ascii.h"
#include "absl/strings/match.h"
#include "absl/strings/str_cat.h"
#include "client/input_files.h"
#include "client/io_errors.h"
#include "core/io/file_bytes.h"
#include "core/render/mesh_views.h"
#include "core/render/png_codec.h"

namespace membrane::client {
namespace {

struct RenderFlags {
  std::string mesh;
  std::string output;
  int size = 256;
};

absl::Status RunRender(const RenderFlags& flags) {
  if (!absl::EndsWith(absl::AsciiStrToLower(flags.output), ".png")) {
    return absl::InvalidArgumentError(
        absl::StrCat("-o ", flags.output, ": the picture is written as PNG; name it *.png"));
  }
  absl::StatusOr<TriangleMesh> mesh = ReadInputMesh(flags.mesh, /*format_flag=*/"", CancelToken::Never());
  if (!mesh.ok()) return FileErrorAsInvalidInput(mesh.status());
  if (mesh->faces.empty()) {
    return absl::InvalidArgumentError(absl::StrCat(flags.mesh, ": has no faces (not a mesh)"));
  }
  MeshViewOptions options;
  options.view_pixels = flags.size;
  absl::StatusOr<std::string> png = EncodePng(RenderMeshViews(*mesh, options));
  if (!png.ok()) return png.status();
  return FileErrorAsInvalidInput(WriteFileBytes(flags.output, *png));
}

}  // namespace

Command AddRenderCommand(CLI::App& parent) {
  CLI::App* app = parent.add_subcommand(
      "render", "draw a mesh from the front, the side and above into a PNG picture");
  app->footer("Exit status: 0 written; 3 when the mesh cannot be read or has no faces, or the "
              "picture cannot be written.");
  auto flags = std::make_shared<RenderFlags>();
  app->add_option("MESH", flags->mesh, "mesh: .ply .obj .off .stl .drc")->required();
  app->add_option("-o,--output", flags->output, "the PNG picture to write")->required();
  app->add_option("--size", flags->size, "pixels of each of the three square views")
      ->capture_default_str()
      ->check(CLI::Range(16, 4096));
  return Command{app, [flags] { return RunRender(*flags); }};
}

}  // namespace membrane::client
