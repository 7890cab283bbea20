#include "core/io/obj_reader.h"

#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "absl/strings/escaping.h"
#include "absl/strings/str_cat.h"
#include "core/io/ascii_scan.h"
#include "core/io/coordinate_shift.h"
#include "core/io/geometry_checks.h"
#include "core/io/parse_error.h"

namespace membrane {
namespace {

// The 0-based vertex of the face reference `token` ("7", "7/2", "-1//3"), given the vertices
// seen so far; nullopt for a malformed or out-of-range reference.
std::optional<int32_t> ResolveReference(absl::string_view token, size_t vertices_so_far) {
  const absl::string_view index_text = token.substr(0, token.find('/'));
  const std::optional<int64_t> index = ParseInt64(index_text);
  if (!index || *index == 0) return std::nullopt;
  // Positive indices may point forward (some exporters write faces first); they are
  // checked against the final vertex count once the whole file is read.
  const int64_t resolved = *index > 0 ? *index - 1 : static_cast<int64_t>(vertices_so_far) + *index;
  if (resolved < 0 || resolved > std::numeric_limits<int32_t>::max()) return std::nullopt;
  return static_cast<int32_t>(resolved);
}

absl::StatusOr<TriangleMesh> ParseObj(absl::string_view data, absl::string_view source,
                                      bool want_faces) {
  TriangleMesh mesh;
  CoordinateShift shift;
  std::vector<int32_t> polygon;
  LineScanner lines(data);
  absl::string_view line;
  while (lines.Next(&line)) {
    TokenScanner tokens(line, lines.line_offset());
    absl::string_view keyword;
    if (!tokens.Next(&keyword)) continue;
    const auto error = [&](absl::string_view what) {
      return LineError(source, lines.line_number(), tokens.token_offset(), what);
    };
    if (keyword == "v") {
      double point[3];
      for (double& coordinate : point) {
        absl::string_view token;
        if (!tokens.Next(&token)) return error("a \"v\" line needs three coordinates");
        const std::optional<double> value = ParseDouble(token);
        if (!value) {
          return error(
              absl::StrCat("'", absl::CHexEscape(token.substr(0, 32)), "' is not a number"));
        }
        coordinate = *value;
      }
      mesh.vertices.push_back(shift.Narrow(point[0], point[1], point[2]));
    } else if (keyword == "f" && want_faces) {
      polygon.clear();
      absl::string_view token;
      while (tokens.Next(&token)) {
        const std::optional<int32_t> index = ResolveReference(token, mesh.vertices.size());
        if (!index) {
          return error(
              absl::StrCat("bad vertex reference '", absl::CHexEscape(token.substr(0, 32)), "'"));
        }
        polygon.push_back(*index);
      }
      for (size_t i = 2; i < polygon.size(); ++i) {
        mesh.faces.push_back({polygon[0], polygon[i - 1], polygon[i]});
      }
    }
  }
  mesh.origin = shift.origin();
  absl::Status indices = CheckFaceIndices(mesh, source);
  if (!indices.ok()) return indices;
  return mesh;
}

}  // namespace

absl::StatusOr<PointCloud> ReadObjPointCloud(absl::string_view data, absl::string_view source) {
  absl::StatusOr<TriangleMesh> mesh = ParseObj(data, source, /*want_faces=*/false);
  if (!mesh.ok()) return mesh.status();
  return PointCloud{std::move(mesh->vertices), mesh->origin};
}

absl::StatusOr<TriangleMesh> ReadObjMesh(absl::string_view data, absl::string_view source) {
  return ParseObj(data, source, /*want_faces=*/true);
}

}  // namespace membrane
