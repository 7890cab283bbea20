#include "core/io/stl_writer.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>

#include "absl/status/status.h"
#include "absl/strings/str_cat.h"
#include "core/io/binary_scalar.h"

namespace membrane {
namespace {

constexpr size_t kHeaderBytes = 80;

std::array<float, 3> UnitNormal(const Point3f& a, const Point3f& b, const Point3f& c) {
  const double u[3] = {double{b[0]} - a[0], double{b[1]} - a[1], double{b[2]} - a[2]};
  const double v[3] = {double{c[0]} - a[0], double{c[1]} - a[1], double{c[2]} - a[2]};
  const double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
                       u[0] * v[1] - u[1] * v[0]};
  const double length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  if (!(length > 0) || !std::isfinite(length)) return {0, 0, 0};
  return {static_cast<float>(n[0] / length), static_cast<float>(n[1] / length),
          static_cast<float>(n[2] / length)};
}

}  // namespace

absl::StatusOr<std::string> EncodeStlMesh(const TriangleMesh& mesh) {
  if (mesh.faces.size() > std::numeric_limits<uint32_t>::max()) {
    return absl::InvalidArgumentError(
        absl::StrCat("binary STL holds fewer than 2^32 faces; the mesh has ", mesh.faces.size()));
  }
  std::string out = "binary STL written by membrane";
  out.resize(kHeaderBytes, ' ');
  out.reserve(kHeaderBytes + 4 + mesh.faces.size() * 50);
  AppendUint32Le(static_cast<uint32_t>(mesh.faces.size()), &out);
  for (const std::array<int32_t, 3>& face : mesh.faces) {
    const Point3f& a = mesh.vertices[face[0]];
    const Point3f& b = mesh.vertices[face[1]];
    const Point3f& c = mesh.vertices[face[2]];
    for (float value : UnitNormal(a, b, c)) AppendFloat32Le(value, &out);
    for (const Point3f* corner : {&a, &b, &c}) {
      for (float value : *corner) AppendFloat32Le(value, &out);
    }
    out.append(2, '\0');  // attribute byte count, unused
  }
  return out;
}

}  // namespace membrane
