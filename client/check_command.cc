#include "client/check_command.h"

#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "CLI/CLI.hpp"
#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "absl/strings/str_join.h"
#include "client/input_files.h"
#include "client/io_errors.h"
#include "core/mesh/mesh_check.h"

namespace membrane::client {
namespace {

struct CheckFlags {
  std::string mesh;
  std::string input_format;
  bool json = false;
};

const char* YesNo(bool value) { return value ? "yes" : "no"; }

std::string ReportText(const MeshReport& r) {
  return absl::StrFormat(
      "vertices: %d\nfaces: %d\nclosed: %s\nmanifold: %s\noriented: %s\nshells: %d\n"
      "genus: [%s]\nself-intersections: %d\nboundary edges: %d\nnon-manifold edges: %d\n"
      "non-manifold vertices: %d\nmisoriented edges: %d\ndegenerate faces: %d\n"
      "volume: %.9g\n",
      r.vertices, r.faces, YesNo(r.closed), YesNo(r.manifold), YesNo(r.oriented), r.shells,
      absl::StrJoin(r.genus, ", "), r.self_intersections, r.boundary_edges, r.nonmanifold_edges,
      r.nonmanifold_vertices, r.misoriented_edges, r.degenerate_faces, r.volume);
}

// OK for a closed, manifold, oriented mesh; otherwise each failure with the count behind it.
absl::Status Verdict(const std::string& path, const MeshReport& r) {
  std::vector<std::string> failed;
  if (!r.closed)
    failed.push_back(absl::StrCat("not closed (", r.boundary_edges, " boundary edges)"));
  if (!r.manifold) {
    failed.push_back(absl::StrCat("not manifold (", r.nonmanifold_edges, " non-manifold edges, ",
                                  r.nonmanifold_vertices, " non-manifold vertices)"));
  }
  if (!r.oriented) {
    failed.push_back(absl::StrCat("not oriented (", r.misoriented_edges, " misoriented edges)"));
  }
  if (failed.empty()) return absl::OkStatus();
  return absl::FailedPreconditionError(absl::StrCat(path, ": ", absl::StrJoin(failed, ", ")));
}

absl::Status RunCheck(const CheckFlags& flags) {
  absl::StatusOr<TriangleMesh> mesh =
      ReadInputMesh(flags.mesh, flags.input_format, CancelToken::Never());
  if (!mesh.ok()) return FileErrorAsInvalidInput(mesh.status());
  // A face-less file is a point cloud; calling it "closed" (no edge is open) would mislead.
  if (mesh->faces.empty()) {
    return absl::InvalidArgumentError(
        absl::StrCat(InputName(flags.mesh), ": has no faces (not a mesh)"));
  }
  const MeshReport report = CheckMesh(*mesh);
  const std::string text = flags.json ? MeshReportToJson(report) + "\n" : ReportText(report);
  std::fputs(text.c_str(), stdout);
  std::fflush(stdout);
  return Verdict(InputName(flags.mesh), report);
}

}  // namespace

Command AddCheckCommand(CLI::App& parent) {
  CLI::App* app = parent.add_subcommand(
      "check", "check that a mesh is closed, manifold and oriented; print its shells and genus");
  app->footer(
      "Exit status: 0 when the mesh is closed, manifold and oriented; 5 (one line naming what "
      "failed, after the report) when it is not; 3 when the file cannot be read or has no "
      "faces.");
  auto flags = std::make_shared<CheckFlags>();
  app->add_option("MESH", flags->mesh, "mesh: .ply .obj .off .stl .drc, or - for standard input")
      ->required();
  app->add_option("--input-format", flags->input_format,
                  "the mesh's format when its name does not say it: ply obj off stl drc; for - "
                  "it is otherwise told from the first bytes");
  app->add_flag("--json", flags->json, "print the report as one JSON object");
  return Command{app, [flags] { return RunCheck(*flags); }};
}

}  // namespace membrane::client
