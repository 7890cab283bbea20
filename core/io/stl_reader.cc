#include "core/io/stl_reader.h"

#include <array>
#include <cstdint>
#include <cstring>
#include <vector>

#include "absl/container/flat_hash_map.h"
#include "absl/strings/ascii.h"
#include "absl/strings/escaping.h"
#include "absl/strings/match.h"
#include "absl/strings/str_cat.h"
#include "core/io/ascii_scan.h"
#include "core/io/binary_scalar.h"
#include "core/io/coordinate_shift.h"
#include "core/io/parse_error.h"

namespace membrane {
namespace {

constexpr size_t kBinaryHeaderBytes = 80;
constexpr size_t kBinaryPreambleBytes = kBinaryHeaderBytes + 4;  // header and triangle count
constexpr size_t kBinaryTriangleBytes = 50;  // normal, 3 corners, attribute word
constexpr size_t kNormalBytes = 12;

// Merges corners with bitwise-equal coordinates into shared vertices.
class VertexWelder {
 public:
  explicit VertexWelder(TriangleMesh* mesh) : mesh_(mesh) {}

  int32_t Add(const Point3f& p) {
    std::array<uint32_t, 3> key;
    for (int axis = 0; axis < 3; ++axis) {
      // Adding +0 turns -0 into +0, so the two zeros weld together.
      const float value = p[axis] + 0.0f;
      std::memcpy(&key[axis], &value, sizeof(float));
    }
    const auto [it, inserted] =
        index_.try_emplace(key, static_cast<int32_t>(mesh_->vertices.size()));
    if (inserted) mesh_->vertices.push_back(p);
    return it->second;
  }

 private:
  TriangleMesh* mesh_;
  absl::flat_hash_map<std::array<uint32_t, 3>, int32_t> index_;
};

// The caller has checked that `data` holds `triangles` triangles.
TriangleMesh ReadBinary(absl::string_view data, uint64_t triangles) {
  TriangleMesh mesh;
  mesh.faces.reserve(triangles);
  VertexWelder welder(&mesh);
  for (uint64_t t = 0; t < triangles; ++t) {
    const char* corner =
        data.data() + kBinaryPreambleBytes + t * kBinaryTriangleBytes + kNormalBytes;
    std::array<int32_t, 3> face;
    for (int c = 0; c < 3; ++c, corner += 12) {
      Point3f p;
      for (int axis = 0; axis < 3; ++axis) {
        p[axis] = static_cast<float>(
            DecodeScalar(corner + 4 * axis, ScalarType::kFloat32, ByteOrder::kLittleEndian));
      }
      face[c] = welder.Add(p);
    }
    mesh.faces.push_back(face);
  }
  // float32 corners are not moved (see CoordinateShift).
  return mesh;
}

absl::StatusOr<TriangleMesh> ReadAscii(absl::string_view data, absl::string_view source) {
  TriangleMesh mesh;
  CoordinateShift shift;
  VertexWelder welder(&mesh);
  std::vector<int32_t> loop;
  bool ended = false;
  TokenScanner tokens(data);
  absl::string_view token;
  while (!ended && tokens.Next(&token)) {
    if (token == "vertex") {
      double p[3];
      for (double& coordinate : p) {
        absl::string_view number;
        std::optional<double> value;
        if (!tokens.Next(&number) || !(value = ParseDouble(number))) {
          return ParseError(source, tokens.token_offset(), "a \"vertex\" needs three numbers");
        }
        coordinate = *value;
      }
      loop.push_back(welder.Add(shift.Narrow(p[0], p[1], p[2])));
    } else if (token == "endloop") {
      for (size_t i = 2; i < loop.size(); ++i) {
        mesh.faces.push_back({loop[0], loop[i - 1], loop[i]});
      }
      loop.clear();
    } else if (token == "endsolid") {
      ended = true;
    }
  }
  // Requiring "endsolid" catches truncated text, and binary files whose header happens to
  // start with "solid" but whose size is wrong.
  if (!ended || !loop.empty()) {
    return ParseError(source, tokens.token_offset(), "the text ends before \"endsolid\"");
  }
  mesh.origin = shift.origin();
  return mesh;
}

}  // namespace

absl::StatusOr<TriangleMesh> ReadStlMesh(absl::string_view data, absl::string_view source) {
  const bool looks_ascii = absl::StartsWith(absl::StripLeadingAsciiWhitespace(data), "solid");
  if (data.size() >= kBinaryPreambleBytes) {
    const uint64_t triangles = static_cast<uint64_t>(DecodeScalar(
        data.data() + kBinaryHeaderBytes, ScalarType::kUint32, ByteOrder::kLittleEndian));
    const uint64_t needed = kBinaryPreambleBytes + triangles * kBinaryTriangleBytes;
    // Binary files may also start with "solid"; an exact size match says binary.
    if (data.size() == needed || (!looks_ascii && data.size() > needed)) {
      return ReadBinary(data, triangles);
    }
    if (!looks_ascii) {
      const uint64_t whole = (data.size() - kBinaryPreambleBytes) / kBinaryTriangleBytes;
      return ParseError(
          source, kBinaryPreambleBytes + whole * kBinaryTriangleBytes,
          absl::StrCat("the data ends inside triangle ", whole, " of ", triangles,
                       " (binary STL needs ", needed, " bytes, the file has ", data.size(), ")"));
    }
  }
  if (looks_ascii) return ReadAscii(data, source);
  return ParseError(source, 0,
                    absl::StrCat("not an STL file: ", data.size(),
                                 " bytes, too short for binary and not \"solid\" text"));
}

}  // namespace membrane
