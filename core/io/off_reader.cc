#include "core/io/off_reader.h"

#include <cstdint>
#include <optional>
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

// The next line holding anything but a comment, cut at its '#'; false at the end.
bool NextContentLine(LineScanner& lines, absl::string_view* line) {
  while (lines.Next(line)) {
    if (const size_t hash = line->find('#'); hash != absl::string_view::npos) {
      *line = line->substr(0, hash);
    }
    TokenScanner probe(*line, 0);
    absl::string_view token;
    if (probe.Next(&token)) return true;
  }
  return false;
}

std::string Quoted(absl::string_view token) {
  return absl::StrCat("'", absl::CHexEscape(token.substr(0, 32)), "'");
}

absl::StatusOr<TriangleMesh> ParseOff(absl::string_view data, absl::string_view source,
                                      bool want_faces) {
  LineScanner lines(data);
  absl::string_view line;
  const auto error_at = [&](size_t offset, absl::string_view what) {
    return LineError(source, lines.line_number(), offset, what);
  };
  if (!NextContentLine(lines, &line)) {
    return absl::InvalidArgumentError(absl::StrCat(source, ": empty OFF file (no \"OFF\" line)"));
  }
  TokenScanner header(line, lines.line_offset());
  absl::string_view keyword;
  header.Next(&keyword);
  if (keyword != "OFF" && keyword != "COFF" && keyword != "NOFF" && keyword != "CNOFF") {
    return error_at(header.token_offset(),
                    absl::StrCat("expected the keyword OFF, found ", Quoted(keyword)));
  }
  // The counts follow on the same line or on the next one.
  absl::string_view count_token;
  TokenScanner counts = header;
  if (!counts.Next(&count_token)) {
    if (!NextContentLine(lines, &line)) {
      return absl::InvalidArgumentError(absl::StrCat(source, ": the OFF header has no counts"));
    }
    counts = TokenScanner(line, lines.line_offset());
    counts.Next(&count_token);
  }
  int64_t announced[2] = {0, 0};
  for (int k = 0; k < 2; ++k) {
    const std::optional<int64_t> value = ParseInt64(count_token);
    // Each vertex or face takes at least 2 bytes: a count past that is a lie that must not
    // size an allocation.
    if (!value || *value < 0 || *value > static_cast<int64_t>(data.size() / 2)) {
      return error_at(counts.token_offset(),
                      absl::StrCat(k == 0 ? "vertex" : "face", " count ", Quoted(count_token),
                                   " is not a number of at most ", data.size() / 2,
                                   " (what this file's size can hold)"));
    }
    announced[k] = *value;
    if (k == 0 && !counts.Next(&count_token)) {
      return error_at(counts.token_offset(), "the counts line needs the vertex and face counts");
    }
  }
  TriangleMesh mesh;
  CoordinateShift shift;
  mesh.vertices.reserve(static_cast<size_t>(announced[0]));
  for (int64_t v = 0; v < announced[0]; ++v) {
    if (!NextContentLine(lines, &line)) {
      return absl::InvalidArgumentError(absl::StrCat(
          source, ": the header announces ", announced[0], " vertices but the file holds ", v));
    }
    TokenScanner tokens(line, lines.line_offset());
    double point[3];
    for (double& coordinate : point) {
      absl::string_view token;
      if (!tokens.Next(&token)) {
        return error_at(tokens.token_offset(), "a vertex line needs three coordinates");
      }
      const std::optional<double> value = ParseDouble(token);
      if (!value) return error_at(tokens.token_offset(), Quoted(token) + " is not a number");
      coordinate = *value;
    }
    mesh.vertices.push_back(shift.Narrow(point[0], point[1], point[2]));
  }
  mesh.origin = shift.origin();
  if (!want_faces) return mesh;
  std::vector<int32_t> polygon;
  for (int64_t f = 0; f < announced[1]; ++f) {
    if (!NextContentLine(lines, &line)) {
      return absl::InvalidArgumentError(absl::StrCat(
          source, ": the header announces ", announced[1], " faces but the file holds ", f));
    }
    TokenScanner tokens(line, lines.line_offset());
    absl::string_view token;
    tokens.Next(&token);
    const std::optional<int64_t> corners = ParseInt64(token);
    if (!corners || *corners < 0 || *corners > static_cast<int64_t>(line.size())) {
      return error_at(tokens.token_offset(), Quoted(token) + " is not a face's vertex count");
    }
    polygon.clear();
    for (int64_t c = 0; c < *corners; ++c) {
      if (!tokens.Next(&token)) {
        return error_at(tokens.token_offset(),
                        absl::StrCat("the face announces ", *corners, " vertices but lists ", c));
      }
      const std::optional<int64_t> index = ParseInt64(token);
      if (!index || *index < 0 || *index >= static_cast<int64_t>(mesh.vertices.size())) {
        return error_at(tokens.token_offset(),
                        absl::StrCat("vertex index ", Quoted(token), " is not in [0, ",
                                     mesh.vertices.size(), ")"));
      }
      polygon.push_back(static_cast<int32_t>(*index));
    }
    for (size_t i = 2; i < polygon.size(); ++i) {
      mesh.faces.push_back({polygon[0], polygon[i - 1], polygon[i]});
    }
  }
  if (absl::Status indices = CheckFaceIndices(mesh, source); !indices.ok()) return indices;
  return mesh;
}

}  // namespace

absl::StatusOr<PointCloud> ReadOffPointCloud(absl::string_view data, absl::string_view source) {
  absl::StatusOr<TriangleMesh> mesh = ParseOff(data, source, /*want_faces=*/false);
  if (!mesh.ok()) return mesh.status();
  return PointCloud{std::move(mesh->vertices), mesh->origin};
}

absl::StatusOr<TriangleMesh> ReadOffMesh(absl::string_view data, absl::string_view source) {
  return ParseOff(data, source, /*want_faces=*/true);
}

}  // namespace membrane
