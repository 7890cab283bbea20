#include "core/io/draco_codec.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <limits>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include "absl/strings/str_cat.h"
#include "core/io/binary_scalar.h"
#include "core/io/draco_header.h"
#include "core/io/geometry_checks.h"
#include "draco/compression/decode.h"
#include "draco/compression/encode.h"
#include "draco/mesh/mesh.h"
#include "draco/point_cloud/point_cloud.h"

namespace membrane {
namespace {

constexpr int kMaxQuantizationBits = 30;
constexpr int kMaxCompressionLevel = 10;
constexpr absl::string_view kSource = "Draco data";

static_assert(sizeof(Point3f) == 3 * sizeof(float), "positions are copied to Draco in bulk");

absl::Status EncoderError(const draco::Status& status) {
  return absl::InternalError(absl::StrCat("the Draco encoder failed: ", status.error_msg_string()));
}

absl::Status DecoderError(const draco::Status& status) {
  return absl::InvalidArgumentError(
      absl::StrCat("not valid Draco data: ", status.error_msg_string()));
}

// Gives `pc` one float32 position attribute with a value per point, in point order.
void SetPositions(const std::vector<Point3f>& positions, draco::PointCloud* pc) {
  const auto count = static_cast<draco::PointIndex::ValueType>(positions.size());
  pc->set_num_points(count);
  draco::GeometryAttribute position;
  position.Init(draco::GeometryAttribute::POSITION, nullptr, 3, draco::DT_FLOAT32, false,
                sizeof(Point3f), 0);
  const int id = pc->AddAttribute(position, /*identity_mapping=*/true, count);
  pc->attribute(id)->buffer()->Write(0, positions.data(), positions.size() * sizeof(Point3f));
}

absl::Status CheckEncodable(const std::vector<Point3f>& positions, const DracoOptions& options,
                            bool is_mesh) {
  const absl::string_view what = is_mesh ? "mesh" : "point cloud";
  absl::Status status = ValidateDracoOptions(options);
  if (!status.ok()) return status;
  if (positions.empty()) {
    return absl::InvalidArgumentError(absl::StrCat("cannot Draco-encode an empty ", what));
  }
  if (positions.size() > static_cast<size_t>(std::numeric_limits<int32_t>::max())) {
    return absl::InvalidArgumentError(
        absl::StrCat("too many points for Draco: ", positions.size()));
  }
  status = CheckFinitePoints(positions, absl::StrCat("cannot Draco-encode the ", what), is_mesh);
  if (!status.ok() || !options.box || options.position_quantization_bits == 0) return status;
  // Draco does not clamp: a value off the grid's ends would get an integer out of its range.
  // Tested on the integer Draco computes (PositionGrid::Snap's float operations).
  const PositionBox& box = *options.box;
  const PositionGrid grid{options.position_quantization_bits, box};
  const float inverse_delta = grid.InverseDelta();
  for (size_t i = 0; i < positions.size(); ++i)
    for (int axis = 0; axis < 3; ++axis) {
      const float q = std::floor(grid.Scaled(positions[i][axis], axis, inverse_delta) + 0.5f);
      if (!(q >= 0 && q <= static_cast<float>(grid.max_quantized()))) {
        return absl::InvalidArgumentError(absl::StrCat(
            "cannot Draco-encode the ", what, ": position ", i, " lies outside the quantization "
            "box (axis ", axis, ": ", positions[i][axis], " not in [", box.origin[axis], ", ",
            box.origin[axis] + box.range, "])"));
      }
    }
  return absl::OkStatus();
}

void Configure(const DracoOptions& options, draco::Encoder* encoder) {
  const int speed = kMaxCompressionLevel - options.compression_level;
  encoder->SetSpeedOptions(speed, speed);
  if (options.position_quantization_bits > 0 && options.box) {
    encoder->SetAttributeExplicitQuantization(draco::GeometryAttribute::POSITION,
                                              options.position_quantization_bits, 3,
                                              options.box->origin.data(), options.box->range);
  } else if (options.position_quantization_bits > 0) {
    encoder->SetAttributeQuantization(draco::GeometryAttribute::POSITION,
                                      options.position_quantization_bits);
  }
}

DracoEncoding Finish(const draco::EncoderBuffer& buffer, const std::vector<Point3f>& positions,
                     const DracoOptions& options) {
  DracoEncoding encoding;
  encoding.bytes.assign(buffer.data(), buffer.size());
  encoding.max_position_error = DracoPositionErrorBound(positions, options);
  return encoding;
}

// The position attribute of decoded geometry, checked so that reading any of its values
// stays inside its buffer (the decoder's output is not trusted either).
absl::StatusOr<const draco::PointAttribute*> CheckedPositions(const draco::PointCloud& pc) {
  const draco::PointAttribute* position = pc.GetNamedAttribute(draco::GeometryAttribute::POSITION);
  if (position == nullptr) {
    return absl::InvalidArgumentError("the Draco data has no position attribute");
  }
  if (position->num_components() != 3) {
    return absl::InvalidArgumentError(absl::StrCat(
        "Draco positions have ", int{position->num_components()}, " components, not 3"));
  }
  switch (position->data_type()) {
    case draco::DT_FLOAT32:
    case draco::DT_FLOAT64:
    case draco::DT_INT8:
    case draco::DT_UINT8:
    case draco::DT_INT16:
    case draco::DT_UINT16:
    case draco::DT_INT32:
    case draco::DT_UINT32: break;
    default:
      // Notably DT_BOOL: Draco would load arbitrary bytes as bool, which is undefined.
      return absl::InvalidArgumentError("Draco positions have an unsupported data type");
  }
  const int64_t value_bytes = 3 * draco::DataTypeLength(position->data_type());
  const size_t count = position->size();
  if (value_bytes == 0 || position->buffer() == nullptr ||
      (count > 0 &&
       position->byte_offset() + position->byte_stride() * int64_t(count - 1) + value_bytes >
           static_cast<int64_t>(position->buffer()->data_size()))) {
    return absl::InvalidArgumentError("the Draco position attribute is inconsistent");
  }
  return position;
}

// The position value of `point`, or nullopt when a crafted file maps it nowhere.
std::optional<draco::AttributeValueIndex> SafeMappedIndex(const draco::PointAttribute& position,
                                                          draco::PointIndex point) {
  if (!position.is_mapping_identity() && point.value() >= position.indices_map_size()) {
    return std::nullopt;
  }
  return position.mapped_index(point);
}

absl::StatusOr<Point3f> PositionValue(const draco::PointAttribute& position,
                                      draco::AttributeValueIndex index) {
  if (index.value() >= position.size()) {
    return absl::InvalidArgumentError("a Draco point maps outside the position values");
  }
  double value[3];
  if (!position.ConvertValue<double>(index, 3, value)) {
    return absl::InvalidArgumentError("Draco positions cannot be converted to float");
  }
  return Point3f{NarrowToFloat(value[0]), NarrowToFloat(value[1]), NarrowToFloat(value[2])};
}

absl::StatusOr<std::vector<Point3f>> AllPositionValues(const draco::PointAttribute& position) {
  std::vector<Point3f> values;
  values.reserve(position.size());
  for (uint32_t i = 0; i < position.size(); ++i) {
    absl::StatusOr<Point3f> value = PositionValue(position, draco::AttributeValueIndex(i));
    if (!value.ok()) return value.status();
    values.push_back(*value);
  }
  return values;
}

absl::string_view DataTypeName(draco::DataType type) {
  static constexpr absl::string_view kNames[] = {"invalid", "int8",   "uint8",   "int16",
                                                 "uint16",  "int32",  "uint32",  "int64",
                                                 "uint64",  "float32", "float64", "bool"};
  const int index = static_cast<int>(type);
  return index >= 0 && index < static_cast<int>(std::size(kNames)) ? kNames[index] : "unknown";
}

// DecodedDracoCloud::attributes of `pc`.
std::string AttributeSignature(const draco::PointCloud& pc) {
  std::string signature;
  for (int i = 0; i < pc.num_attributes(); ++i) {
    const draco::PointAttribute& a = *pc.attribute(i);
    absl::StrAppend(&signature, i > 0 ? ", " : "",
                    draco::GeometryAttribute::TypeToString(a.attribute_type()), " ",
                    DataTypeName(a.data_type()), " x", int{a.num_components()});
  }
  return signature;
}

}  // namespace

double DracoPositionErrorBound(const std::vector<Point3f>& positions, const DracoOptions& options) {
  const int bits = options.position_quantization_bits;
  if (bits == 0) return 0;
  double range = 0, magnitude = 0;
  for (int axis = 0; axis < 3; ++axis) {
    float low = std::numeric_limits<float>::max(), high = std::numeric_limits<float>::lowest();
    for (const Point3f& p : positions) {
      low = std::min(low, p[axis]);
      high = std::max(high, p[axis]);
    }
    range = std::max(range, double{high} - low);
    magnitude = std::max({magnitude, std::fabs(double{low}), std::fabs(double{high})});
  }
  if (options.box) range = options.box->range;
  // Draco quantizes a flat (zero-range) attribute over a range of 1.
  if (range == 0) range = 1;
  const double half_step = range / (std::ldexp(1.0, bits) - 1) / 2;
  // Dequantization computes q * step + min in float32: a few rounding units of the range
  // and of the largest coordinate.
  const double rounding = 4 * FLT_EPSILON * (range + magnitude);
  return half_step + rounding;
}

absl::Status ValidateDracoOptions(const DracoOptions& options) {
  const int bits = options.position_quantization_bits;
  if (bits < 0 || bits > kMaxQuantizationBits) {
    return absl::InvalidArgumentError(absl::StrCat("position_quantization_bits is ", bits,
                                                   "; it must be 0 (lossless) or 1..",
                                                   kMaxQuantizationBits));
  }
  const int level = options.compression_level;
  if (level < 0 || level > kMaxCompressionLevel) {
    return absl::InvalidArgumentError(
        absl::StrCat("compression_level is ", level, "; it must be in 0..", kMaxCompressionLevel));
  }
  if (options.box) {
    const PositionBox& box = *options.box;
    const bool finite = std::isfinite(box.origin[0]) && std::isfinite(box.origin[1]) &&
                        std::isfinite(box.origin[2]) && std::isfinite(box.range);
    if (!finite || !(box.range > 0)) {
      return absl::InvalidArgumentError(absl::StrCat(
          "the quantization box (origin ", box.origin[0], " ", box.origin[1], " ", box.origin[2],
          ", range ", box.range, ") must be finite with a positive range"));
    }
  }
  return absl::OkStatus();
}

absl::StatusOr<DracoEncoding> EncodeDracoPointCloud(const PointCloud& cloud,
                                                    const DracoOptions& options) {
  absl::Status status = CheckEncodable(cloud.points, options, /*is_mesh=*/false);
  if (!status.ok()) return status;
  draco::PointCloud pc;
  SetPositions(cloud.points, &pc);
  draco::Encoder encoder;
  Configure(options, &encoder);
  draco::EncoderBuffer buffer;
  const draco::Status encoded = encoder.EncodePointCloudToBuffer(pc, &buffer);
  if (!encoded.ok()) return EncoderError(encoded);
  return Finish(buffer, cloud.points, options);
}

absl::StatusOr<DracoEncoding> EncodeDracoMesh(const TriangleMesh& mesh,
                                              const DracoOptions& options) {
  absl::Status status = CheckEncodable(mesh.vertices, options, /*is_mesh=*/true);
  if (!status.ok()) return status;
  if (mesh.faces.empty()) {
    return absl::InvalidArgumentError("cannot Draco-encode a mesh without faces");
  }
  status = CheckFaceIndices(mesh, "cannot Draco-encode the mesh");
  if (!status.ok()) return status;
  draco::Mesh dm;
  SetPositions(mesh.vertices, &dm);
  dm.SetNumFaces(mesh.faces.size());
  for (size_t f = 0; f < mesh.faces.size(); ++f) {
    const std::array<int32_t, 3>& face = mesh.faces[f];
    dm.SetFace(draco::FaceIndex(static_cast<uint32_t>(f)),
               {draco::PointIndex(static_cast<uint32_t>(face[0])),
                draco::PointIndex(static_cast<uint32_t>(face[1])),
                draco::PointIndex(static_cast<uint32_t>(face[2]))});
  }
  draco::Encoder encoder;
  Configure(options, &encoder);
  draco::EncoderBuffer buffer;
  const draco::Status encoded = encoder.EncodeMeshToBuffer(dm, &buffer);
  if (!encoded.ok()) return EncoderError(encoded);
  return Finish(buffer, mesh.vertices, options);
}

absl::StatusOr<DracoGeometry> DracoGeometryOf(absl::string_view bytes) {
  draco::DecoderBuffer buffer;
  buffer.Init(bytes.data(), bytes.size());
  draco::StatusOr<draco::EncodedGeometryType> type =
      draco::Decoder::GetEncodedGeometryType(&buffer);
  if (!type.ok()) return DecoderError(type.status());
  switch (type.value()) {
    case draco::POINT_CLOUD: return DracoGeometry::kPointCloud;
    case draco::TRIANGULAR_MESH: return DracoGeometry::kMesh;
    default: return absl::InvalidArgumentError("the Draco data holds no known geometry type");
  }
}

absl::StatusOr<DecodedDracoCloud> DecodeDracoPointCloud(absl::string_view bytes,
                                                        DracoMeshPolicy policy) {
  absl::StatusOr<DracoGeometry> geometry = DracoGeometryOf(bytes);
  if (!geometry.ok()) return geometry.status();
  if (*geometry == DracoGeometry::kMesh && policy == DracoMeshPolicy::kRejectMesh) {
    return absl::InvalidArgumentError(
        "the Draco data holds a mesh where a point cloud is required");
  }
  if (*geometry == DracoGeometry::kPointCloud) {
    absl::Status count = CheckDracoPointCloudHeader(bytes);
    if (!count.ok()) return count;
  }
  draco::DecoderBuffer buffer;
  buffer.Init(bytes.data(), bytes.size());
  draco::Decoder decoder;
  draco::StatusOr<std::unique_ptr<draco::PointCloud>> decoded =
      decoder.DecodePointCloudFromBuffer(&buffer);
  if (!decoded.ok()) return DecoderError(decoded.status());
  const draco::PointCloud& pc = *decoded.value();
  absl::StatusOr<const draco::PointAttribute*> position = CheckedPositions(pc);
  if (!position.ok()) return position.status();
  DecodedDracoCloud result;
  result.geometry = *geometry;
  result.attributes = AttributeSignature(pc);
  if (*geometry == DracoGeometry::kMesh) {
    absl::StatusOr<std::vector<Point3f>> values = AllPositionValues(**position);
    if (!values.ok()) return values.status();
    result.cloud.points = std::move(*values);
  } else {
    result.cloud.points.reserve(pc.num_points());
    for (uint32_t p = 0; p < pc.num_points(); ++p) {
      const std::optional<draco::AttributeValueIndex> index =
          SafeMappedIndex(**position, draco::PointIndex(p));
      if (!index) return absl::InvalidArgumentError("a Draco point has no position");
      absl::StatusOr<Point3f> value = PositionValue(**position, *index);
      if (!value.ok()) return value.status();
      result.cloud.points.push_back(*value);
    }
  }
  absl::Status finite = CheckFinitePoints(result.cloud.points, kSource);
  if (!finite.ok()) return finite;
  return result;
}

absl::StatusOr<TriangleMesh> DecodeDracoMesh(absl::string_view bytes) {
  absl::StatusOr<DracoGeometry> geometry = DracoGeometryOf(bytes);
  if (!geometry.ok()) return geometry.status();
  if (*geometry != DracoGeometry::kMesh) {
    return absl::InvalidArgumentError("the Draco data holds a point cloud, not a mesh");
  }
  draco::DecoderBuffer buffer;
  buffer.Init(bytes.data(), bytes.size());
  draco::Decoder decoder;
  draco::StatusOr<std::unique_ptr<draco::Mesh>> decoded = decoder.DecodeMeshFromBuffer(&buffer);
  if (!decoded.ok()) return DecoderError(decoded.status());
  const draco::Mesh& dm = *decoded.value();
  absl::StatusOr<const draco::PointAttribute*> position = CheckedPositions(dm);
  if (!position.ok()) return position.status();
  if ((*position)->size() > static_cast<size_t>(std::numeric_limits<int32_t>::max())) {
    return absl::InvalidArgumentError("the Draco mesh has more vertices than int32 indexes");
  }
  TriangleMesh mesh;
  absl::StatusOr<std::vector<Point3f>> values = AllPositionValues(**position);
  if (!values.ok()) return values.status();
  mesh.vertices = std::move(*values);
  mesh.faces.reserve(dm.num_faces());
  for (uint32_t f = 0; f < dm.num_faces(); ++f) {
    const draco::Mesh::Face& face = dm.face(draco::FaceIndex(f));
    std::array<int32_t, 3> corners;
    for (int c = 0; c < 3; ++c) {
      const std::optional<draco::AttributeValueIndex> index =
          face[c].value() < dm.num_points() ? SafeMappedIndex(**position, face[c]) : std::nullopt;
      if (!index) {
        return absl::InvalidArgumentError("a Draco face refers to a point that does not exist");
      }
      // Value indices, not point indices: points that differ only in other attributes
      // (normals, texture coordinates) are one vertex of the surface. Range-checked below.
      corners[c] = static_cast<int32_t>(std::min<uint32_t>(
          index->value(), static_cast<uint32_t>(std::numeric_limits<int32_t>::max())));
    }
    mesh.faces.push_back(corners);
  }
  absl::Status status = CheckFinitePoints(mesh.vertices, kSource, /*is_mesh=*/true);
  if (status.ok()) status = CheckFaceIndices(mesh, kSource);
  if (!status.ok()) return status;
  return mesh;
}

}  // namespace membrane
