#include "client/convert_command.h"

#include <cstdio>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "CLI/CLI.hpp"
#include "absl/algorithm/container.h"
#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "client/flag_checks.h"
#include "client/format_flags.h"
#include "client/input_files.h"
#include "client/io_errors.h"
#include "client/output_files.h"
#include "client/std_streams.h"
#include "core/io/draco_codec.h"
#include "core/io/file_format.h"
#include "core/io/point_cloud_io.h"
#include "core/mesh/mesh_check.h"

namespace membrane::client {
namespace {

struct ConvertFlags {
  std::string input;  // "-": standard input
  std::string input_format;
  std::string output;  // "-": standard output
  std::string output_format;
  bool drop_invalid = false;
};

// The format of the input `path` (InputFormat; `bytes` as read, for "-") for reading anything:
// a point cloud or a mesh.
absl::StatusOr<FileFormat> AnyInputFormat(const ConvertFlags& flags, absl::string_view bytes) {
  absl::StatusOr<FileFormat> format =
      InputFormat(flags.input, flags.input_format, FileUse::kReadPointCloud, bytes);
  if (format.ok()) return format;
  absl::StatusOr<FileFormat> mesh_format =
      InputFormat(flags.input, flags.input_format, FileUse::kReadMesh, bytes);
  if (mesh_format.ok()) return mesh_format;
  return format.status();
}

// The format of the output (OutputFormat) for writing anything: a point cloud or a mesh.
absl::StatusOr<FileFormat> AnyOutputFormat(const ConvertFlags& flags) {
  absl::StatusOr<FileFormat> format =
      OutputFormat(flags.output, flags.output_format, FileUse::kWritePointCloud);
  if (format.ok()) return format;
  absl::StatusOr<FileFormat> mesh_format =
      OutputFormat(flags.output, flags.output_format, FileUse::kWriteMesh);
  if (mesh_format.ok()) return mesh_format;
  return format.status();
}

bool Supports(FileUse use, FileFormat format) {
  return absl::c_linear_search(SupportedFormats(use), format);
}

// True when a file of `format` holding `bytes` is to be read as a mesh. PLY, OBJ, STL, OFF
// and Draco can hold meshes; a Draco file says in its header which it holds.
absl::StatusOr<bool> HoldsMesh(FileFormat format, const std::string& bytes,
                               const std::string& path) {
  switch (format) {
    case FileFormat::kXyz:
    case FileFormat::kPcd: return false;
    case FileFormat::kDrc: {
      absl::StatusOr<DracoGeometry> geometry = DracoGeometryOf(bytes);
      if (!geometry.ok()) {
        return absl::InvalidArgumentError(absl::StrCat(path, ": ", geometry.status().message()));
      }
      return *geometry == DracoGeometry::kMesh;
    }
    default: return true;
  }
}

// `bytes`, the contents of `path` in `format`, as a mesh; a file without faces gives a mesh
// without faces. With InvalidPoints::kDrop (--drop-invalid) the file is read as a point
// cloud, its points with NaN or infinite coordinates left out and counted in `dropped`.
absl::StatusOr<TriangleMesh> ParseGeometry(const std::string& bytes, FileFormat format,
                                           const std::string& path, InvalidPoints invalid,
                                           size_t* dropped) {
  *dropped = 0;
  absl::StatusOr<bool> holds_mesh = HoldsMesh(format, bytes, path);
  if (!holds_mesh.ok()) return holds_mesh.status();
  const bool cloud_format = Supports(FileUse::kReadPointCloud, format);
  if (*holds_mesh && !(invalid == InvalidPoints::kDrop && cloud_format)) {
    absl::StatusOr<TriangleMesh> mesh = ParseInputMesh(bytes, format, path, CancelToken::Never());
    if (mesh.ok() || !cloud_format) return mesh;
    // A PLY of an organized scan holds no faces, and NaN where a pixel had no return: say
    // so, and what drops them, rather than only that the vertices are not finite.
    size_t count = 0;
    if (ReadPointCloudFromBuffer(bytes, format, path, InvalidPoints::kDrop, &count).ok() &&
        count > 0) {
      return InvalidPointsError(path, count);
    }
    return mesh;
  }
  absl::StatusOr<PointCloud> cloud =
      ParseInputCloud(bytes, format, path, CancelToken::Never(), invalid, dropped);
  if (!cloud.ok()) return cloud.status();
  TriangleMesh points_only;
  points_only.vertices = std::move(cloud->points);
  points_only.origin = cloud->origin;
  return points_only;
}

// The Draco options for writing `mesh`: 11-bit positions, snapped here first (on a grid that
// stores them exactly), unless that makes more faces cross or flatten than the input has;
// then float32, with a line on `text` saying why. `mesh` keeps its snapped positions when
// they are kept.
DracoOptions CheckedDracoOptions(TriangleMesh& mesh, std::FILE* text) {
  const DracoOptions defaults;
  const PositionGrid grid = BoundingGrid(mesh.vertices, defaults.position_quantization_bits);
  TriangleMesh snapped = mesh;
  for (Point3f& p : snapped.vertices) p = grid.Snap(p);
  const MeshReport before = CheckMesh(mesh), after = CheckMesh(snapped);
  if (after.self_intersections > before.self_intersections ||
      after.degenerate_faces > before.degenerate_faces) {
    std::fprintf(text, "%d-bit positions would give %lld crossing face pairs and %lld flat faces "
                "(the input has %lld and %lld): writing float32 positions\n",
                grid.bits, static_cast<long long>(after.self_intersections),
                static_cast<long long>(after.degenerate_faces),
                static_cast<long long>(before.self_intersections),
                static_cast<long long>(before.degenerate_faces));
    DracoOptions lossless = defaults;
    lossless.position_quantization_bits = 0;
    return lossless;
  }
  mesh = std::move(snapped);
  return DracoOptionsOnGrid(grid, defaults.compression_level);
}

// What a .drc file's quantization does to the positions written, for the line that reports it:
// "" for other formats.
std::string DracoErrorNote(FileFormat format, const std::vector<Point3f>& positions,
                           const DracoOptions& draco) {
  if (format != FileFormat::kDrc) return "";
  if (draco.position_quantization_bits == 0) return " (lossless positions)";
  return absl::StrFormat(" (%d-bit positions: each coordinate within %.3g of the input's)",
                         draco.position_quantization_bits,
                         DracoPositionErrorBound(positions, draco));
}

absl::Status RunConvert(const ConvertFlags& flags) {
  // Both names are checked before any reading (standard input's format may have to wait for
  // its first bytes).
  if (!IsStdStream(flags.input) || !flags.input_format.empty()) {
    if (absl::Status s = AnyInputFormat(flags, "").status(); !s.ok()) return s;
  }
  absl::StatusOr<FileFormat> out_format = AnyOutputFormat(flags);
  if (!out_format.ok()) return out_format.status();
  if (absl::Status s = CheckOutputPath("OUTPUT", flags.output); !s.ok()) return s;

  absl::StatusOr<std::string> bytes = ReadInputBytes(flags.input);
  if (!bytes.ok()) return FileErrorAsInvalidInput(bytes.status());
  absl::StatusOr<FileFormat> in_format = AnyInputFormat(flags, *bytes);
  if (!in_format.ok()) return in_format.status();
  const std::string input = InputName(flags.input), output = OutputName(flags.output);
  size_t dropped = 0;
  absl::StatusOr<TriangleMesh> geometry = ParseGeometry(
      *bytes, *in_format, input,
      flags.drop_invalid ? InvalidPoints::kDrop : InvalidPoints::kRefuse, &dropped);
  if (!geometry.ok()) return geometry.status();
  // A text file that is no OBJ (or an empty PLY) parses as no points: an error, not a file of
  // nothing reported as converted.
  if (geometry->vertices.empty()) {
    return absl::InvalidArgumentError(absl::StrCat(
        "'", input, "' holds no points (is it really ", FormatName(*in_format), "?)"));
  }
  // Standard output carries the result: the lines about it go to stderr then.
  std::FILE* text = IsStdStream(flags.output) ? stderr : stdout;
  const bool keep_faces = !geometry->faces.empty() && Supports(FileUse::kWriteMesh, *out_format);
  if (keep_faces) {
    DracoOptions draco;
    // The bound is taken on the input's positions, before CheckedDracoOptions snaps them.
    const std::vector<Point3f> input_vertices =
        *out_format == FileFormat::kDrc ? geometry->vertices : std::vector<Point3f>{};
    if (*out_format == FileFormat::kDrc) draco = CheckedDracoOptions(*geometry, text);
    if (absl::Status s = WriteOutputMesh(*geometry, flags.output, *out_format, draco); !s.ok()) {
      return s;
    }
    std::fprintf(text, "wrote a mesh of %zu vertices and %zu faces to %s%s\n",
                 geometry->vertices.size(), geometry->faces.size(), output.c_str(),
                 DracoErrorNote(*out_format, input_vertices, draco).c_str());
    return absl::OkStatus();
  }
  if (!Supports(FileUse::kWritePointCloud, *out_format)) {
    return absl::InvalidArgumentError(absl::StrCat(input, " has no faces, and ",
                                                   FormatName(*out_format), " holds only meshes"));
  }
  PointCloud cloud;
  cloud.points = std::move(geometry->vertices);
  cloud.origin = geometry->origin;
  const DracoOptions draco;
  if (absl::Status s = WriteOutputCloud(cloud, flags.output, *out_format, draco); !s.ok()) {
    return s;
  }
  const std::string dropped_note =
      dropped > 0 ? absl::StrCat(" (", DroppedPointsNote(dropped), ")") : std::string();
  std::fprintf(text, "wrote %zu points to %s%s%s\n", cloud.points.size(), output.c_str(),
               dropped_note.c_str(), DracoErrorNote(*out_format, cloud.points, draco).c_str());
  return absl::OkStatus();
}

}  // namespace

Command AddConvertCommand(CLI::App& parent) {
  CLI::App* app = parent.add_subcommand(
      "convert", "convert a point cloud or a mesh between formats (chosen by extension)");
  auto flags = std::make_shared<ConvertFlags>();
  app->add_option("INPUT", flags->input,
                  "point cloud or mesh: .ply .obj .off .xyz .txt .pts .pcd .stl .drc, or - for "
                  "standard input")
      ->required();
  app->add_option("OUTPUT", flags->output,
                  "point cloud or mesh: .ply .obj .xyz .stl .drc, or - for standard output")
      ->required();
  app->add_option("--input-format", flags->input_format,
                  "the input's format when its name does not say it: ply obj off xyz pcd stl "
                  "drc; for - it is otherwise told from the first bytes");
  app->add_option("--output-format", flags->output_format,
                  "the output's format when its name does not say it: ply obj xyz stl drc; for "
                  "- it is otherwise binary PLY");
  app->add_flag("--drop-invalid", flags->drop_invalid,
                "read INPUT as a point cloud and leave out the points with NaN or infinite "
                "coordinates (how organized scans mark pixels without a return) instead of "
                "refusing it; the count is reported");
  return Command{app, [flags] { return RunConvert(*flags); }};
}

}  // namespace membrane::client
