#include "core/io/ply_body.h"

#include <cmath>
#include <cstdint>
#include <limits>
#include <type_traits>
#include <vector>

#include "absl/status/status.h"
#include "absl/strings/str_cat.h"
#include "core/io/binary_scalar.h"
#include "core/io/coordinate_shift.h"
#include "core/io/parse_error.h"
#include "core/io/ply_value_source.h"
#include "core/io/ply_vertex_rows.h"

namespace membrane {
namespace {

// What the walker does with one element.
struct ElementPlan {
  enum class Role { kSkip, kVertex, kFace };
  Role role = Role::kSkip;
  size_t x = 0, y = 0, z = 0;  // property indices, for kVertex
  size_t indices = 0;          // the index list property, for kFace
};

// Largest double below 2^64 that is still a list length worth converting; anything larger
// cannot fit in any file.
constexpr double kMaxListLength = 9.0e18;

bool HasLists(const PlyElement& element) {
  for (const PlyProperty& property : element.properties) {
    if (property.list_count_type) return true;
  }
  return false;
}

absl::StatusOr<ElementPlan> PlanVertex(const PlyElement& element, absl::string_view source) {
  ElementPlan plan;
  plan.role = ElementPlan::Role::kVertex;
  size_t* slots[3] = {&plan.x, &plan.y, &plan.z};
  const char* names[3] = {"x", "y", "z"};
  for (int axis = 0; axis < 3; ++axis) {
    std::optional<size_t> index = FindPlyProperty(element, names[axis]);
    if (!index || element.properties[*index].list_count_type) {
      return absl::InvalidArgumentError(
          absl::StrCat(source, ": the vertex element has no scalar property '", names[axis], "'"));
    }
    *slots[axis] = *index;
  }
  return plan;
}

absl::StatusOr<ElementPlan> PlanFace(const PlyElement& element, absl::string_view source) {
  ElementPlan plan;
  plan.role = ElementPlan::Role::kFace;
  std::optional<size_t> index = FindPlyProperty(element, "vertex_indices");
  if (!index) index = FindPlyProperty(element, "vertex_index");
  if (!index || !element.properties[*index].list_count_type) {
    return absl::InvalidArgumentError(absl::StrCat(
        source, ": the face element has no list property 'vertex_indices' or 'vertex_index'"));
  }
  plan.indices = *index;
  return plan;
}

// True when the vertex element stores x, y and z as float32 (CoordinateShift::NarrowStored).
bool Float32Positions(const PlyElement& element, const ElementPlan& plan) {
  for (size_t p : {plan.x, plan.y, plan.z})
    if (element.properties[p].type != ScalarType::kFloat32) return false;
  return true;
}

// Binary elements without lists have fixed-size rows: the vertex block of a scan is read
// with one bounds check instead of one per value.
absl::Status ReadFixedRows(const PlyElement& element, const ElementPlan& plan,
                           absl::string_view source, PlyBinarySource& in, CoordinateShift& shift,
                           TriangleMesh* out) {
  const PlyVertexRows layout = VertexRowLayout(element, plan.x, plan.y, plan.z, in.order());
  const size_t row_bytes = layout.row_bytes;
  const size_t start = in.offset();
  if (!in.MayHoldRows(element.count, row_bytes)) {
    const uint64_t whole_rows = in.remaining() / row_bytes;
    return ParseError(source, start + whole_rows * row_bytes,
                      absl::StrCat("the data ends inside ", element.name, " ", whole_rows, " of ",
                                   element.count, " (rows of ", row_bytes, " bytes from byte ",
                                   start, "; only ", in.remaining(), " bytes remain)"));
  }
  const char* rows = in.Take(element.count * row_bytes);
  if (plan.role != ElementPlan::Role::kVertex) return absl::OkStatus();
  out->vertices.resize(element.count);
  DecodeVertexRows(rows, element.count, layout, shift, out->vertices.data());
  return absl::OkStatus();
}

// Reads one vertex index list of `length` items and appends its fan triangulation.
template <typename Source>
absl::Status ReadPolygon(uint64_t length, const PlyProperty& property, uint64_t vertex_count,
                         const std::string& where, absl::string_view source, Source& in,
                         std::vector<int32_t>* polygon, TriangleMesh* out) {
  polygon->clear();
  for (uint64_t i = 0; i < length; ++i) {
    double value = 0;
    if (!in.Read(property.type, &value)) {
      return ParseError(source, in.failure_offset(), absl::StrCat(where, ": ", in.problem()));
    }
    if (!(value >= 0) || value != std::floor(value) || value >= static_cast<double>(vertex_count) ||
        value > std::numeric_limits<int32_t>::max()) {
      return ParseError(
          source, in.offset(),
          absl::StrCat(where, ": vertex index ", value, " is not in [0, ", vertex_count, ")"));
    }
    polygon->push_back(static_cast<int32_t>(value));
  }
  for (size_t i = 2; i < polygon->size(); ++i) {
    out->faces.push_back({(*polygon)[0], (*polygon)[i - 1], (*polygon)[i]});
  }
  return absl::OkStatus();
}

template <typename Source>
absl::Status ReadElement(const PlyElement& element, const ElementPlan& plan, uint64_t vertex_count,
                         absl::string_view source, Source& in, CoordinateShift& shift,
                         TriangleMesh* out) {
  // Rows without properties take no bytes: there is nothing to read, however many there are.
  if (element.properties.empty()) return absl::OkStatus();
  if constexpr (std::is_same_v<Source, PlyBinarySource>) {
    if (!HasLists(element)) return ReadFixedRows(element, plan, source, in, shift, out);
  }
  const size_t min_row = in.MinRowBytes(element);
  if (!in.MayHoldRows(element.count, min_row)) {
    return ParseError(source, in.offset(),
                      absl::StrCat("the header declares ", element.count, " '", element.name,
                                   "' elements of at least ", min_row, " bytes each, but only ",
                                   in.remaining(), " bytes remain"));
  }
  // Safe now: the count is bounded by the bytes that remain.
  if (plan.role == ElementPlan::Role::kVertex) out->vertices.reserve(element.count);
  if (plan.role == ElementPlan::Role::kFace) out->faces.reserve(element.count);
  const bool binary_float32 = std::is_same_v<Source, PlyBinarySource> &&
                              plan.role == ElementPlan::Role::kVertex &&
                              Float32Positions(element, plan);
  std::vector<double> row(element.properties.size());
  std::vector<int32_t> polygon;
  for (uint64_t r = 0; r < element.count; ++r) {
    for (size_t p = 0; p < element.properties.size(); ++p) {
      const PlyProperty& property = element.properties[p];
      const auto where = [&] {
        return absl::StrCat(element.name, " ", r, " of ", element.count, ", property '",
                            property.name, "'");
      };
      const auto failure = [&] {
        return ParseError(source, in.failure_offset(), absl::StrCat(where(), ": ", in.problem()));
      };
      if (!property.list_count_type) {
        if (!in.Read(property.type, &row[p])) return failure();
        continue;
      }
      double length_value = 0;
      if (!in.Read(*property.list_count_type, &length_value)) return failure();
      if (!(length_value >= 0) || length_value != std::floor(length_value) ||
          length_value > kMaxListLength ||
          !in.MayHold(static_cast<uint64_t>(length_value), property.type)) {
        const std::string length_text = length_value >= 0 && length_value <= kMaxListLength
                                            ? absl::StrCat(static_cast<uint64_t>(length_value))
                                            : absl::StrCat(length_value);
        return ParseError(source, in.offset(),
                          absl::StrCat(where(), ": list length ", length_text,
                                       " is impossible with ", in.remaining(), " bytes remaining"));
      }
      const uint64_t length = static_cast<uint64_t>(length_value);
      if (plan.role == ElementPlan::Role::kFace && p == plan.indices) {
        absl::Status status =
            ReadPolygon(length, property, vertex_count, where(), source, in, &polygon, out);
        if (!status.ok()) return status;
      } else if (!in.Skip(length, property.type)) {
        return failure();
      }
    }
    if (plan.role == ElementPlan::Role::kVertex) {
      out->vertices.push_back(
          shift.NarrowStored(row[plan.x], row[plan.y], row[plan.z], binary_float32));
    }
  }
  return absl::OkStatus();
}

template <typename Source>
absl::StatusOr<TriangleMesh> ReadElements(const PlyHeader& header,
                                          const std::vector<ElementPlan>& plans,
                                          uint64_t vertex_count, absl::string_view source,
                                          Source& in) {
  TriangleMesh mesh;
  CoordinateShift shift;
  for (size_t e = 0; e < header.elements.size(); ++e) {
    absl::Status status =
        ReadElement(header.elements[e], plans[e], vertex_count, source, in, shift, &mesh);
    if (!status.ok()) return status;
  }
  mesh.origin = shift.origin();
  return mesh;
}

}  // namespace

absl::StatusOr<TriangleMesh> ReadPlyBody(absl::string_view data, const PlyHeader& header,
                                         absl::string_view source, bool want_faces) {
  std::vector<ElementPlan> plans(header.elements.size());
  bool have_vertex = false, have_face = false;
  uint64_t vertex_count = 0;
  for (size_t e = 0; e < header.elements.size(); ++e) {
    const PlyElement& element = header.elements[e];
    if (element.name == "vertex" && !have_vertex) {
      absl::StatusOr<ElementPlan> plan = PlanVertex(element, source);
      if (!plan.ok()) return plan.status();
      plans[e] = *plan;
      have_vertex = true;
      vertex_count = element.count;
    } else if (element.name == "face" && want_faces && !have_face) {
      absl::StatusOr<ElementPlan> plan = PlanFace(element, source);
      if (!plan.ok()) return plan.status();
      plans[e] = *plan;
      have_face = true;
    }
  }
  if (!have_vertex) {
    return absl::InvalidArgumentError(absl::StrCat(source, ": the PLY file has no vertex element"));
  }
  switch (header.encoding) {
    case PlyEncoding::kAscii: {
      PlyAsciiSource in(data, header.body_offset);
      return ReadElements(header, plans, vertex_count, source, in);
    }
    case PlyEncoding::kBinaryLittleEndian: {
      PlyBinarySource in(data, header.body_offset, ByteOrder::kLittleEndian);
      return ReadElements(header, plans, vertex_count, source, in);
    }
    case PlyEncoding::kBinaryBigEndian: {
      PlyBinarySource in(data, header.body_offset, ByteOrder::kBigEndian);
      return ReadElements(header, plans, vertex_count, source, in);
    }
  }
  return absl::InternalError("unreachable PLY encoding");
}

}  // namespace membrane
