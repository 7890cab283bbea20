#include "core/io/draco_header.h"

#include <cstddef>
#include <iterator>
#include <optional>

#include "absl/strings/str_cat.h"
#include "core/io/binary_scalar.h"

namespace membrane {
namespace {

constexpr size_t kDracoHeaderBytes = 11;  // "DRACO", 2 version bytes, type, method, flags
constexpr size_t kDracoVersionOffset = 5;  // major, minor
constexpr size_t kDracoTypeOffset = 7;     // 0: point cloud; then the method: 0 or 1 (kd-tree)
constexpr size_t kDracoFlagsOffset = 9;    // uint16, little endian
constexpr uint16_t kDracoMetadataFlag = 0x8000;
// Draco reads a uint32 varint from at most 5 bytes.
constexpr int kMaxVarintBytes = 5;
// A float32 position: what kMaxDracoPointsPerByte was measured with.
constexpr uint64_t kPositionBytes = 12;

// A cursor over a Draco file's bytes after its fixed header, reading the parts in front of
// the coded data as Draco 1.5.5 does; every read fails rather than pass the end.
class HeaderWalker {
 public:
  HeaderWalker(absl::string_view bytes, size_t at) : bytes_(bytes), at_(at) {}

  size_t offset() const { return at_; }

  // Skips the geometry metadata (attribute metadata, then the file's), as Draco's
  // MetadataDecoder reads it. False when it is malformed or does not fit in the data.
  bool SkipGeometryMetadata() {
    const std::optional<uint32_t> attributes = Varint();
    if (!attributes) return false;
    for (uint32_t i = 0; i < *attributes; ++i) {
      if (!Varint() || !SkipMetadata()) return false;  // the attribute's id, its metadata
    }
    return SkipMetadata();
  }

  // Reads the int32 point count of a point cloud's geometry; nullopt at the end of the data.
  std::optional<int32_t> PointCount() {
    const std::optional<uint32_t> count = Uint32();
    if (!count) return std::nullopt;
    return static_cast<int32_t>(*count);
  }

  // The attribute descriptors that follow a point cloud's point count (Draco's
  // PointCloudDecoder::DecodePointAttributes: a count of attribute decoders; then
  // AttributesDecoder::DecodeAttributesDecoderData of each: a count of attributes, and per
  // attribute its type, data type, component count, normalized flag and id): the bytes one
  // point takes once decoded, summed over every attribute. nullopt when the data ends first
  // or names an unknown data type: Draco then fails before it allocates any attribute.
  std::optional<uint64_t> DecodedBytesPerPoint(int major, int minor) {
    const std::optional<uint32_t> decoders = Byte();
    if (!decoders) return std::nullopt;
    const bool fixed_count = major < 2;                          // uint32 before 2.0
    const bool short_id = major < 1 || (major == 1 && minor < 3);  // uint16 before 1.3
    uint64_t per_point = 0;
    for (uint32_t d = 0; d < *decoders; ++d) {
      const std::optional<uint32_t> attributes = fixed_count ? Uint32() : Varint();
      if (!attributes) return std::nullopt;
      for (uint32_t a = 0; a < *attributes; ++a) {
        if (!SkipBytes(1)) return std::nullopt;  // the attribute's type
        const std::optional<uint32_t> data_type = Byte(), components = Byte();
        if (!components || !SkipBytes(1)) return std::nullopt;  // then its normalized flag
        const int length = DataTypeBytes(*data_type);
        if (length == 0) return std::nullopt;
        per_point += static_cast<uint64_t>(length) * *components;
        if (!(short_id ? SkipBytes(2) : Varint().has_value())) return std::nullopt;
      }
    }
    return per_point;
  }

 private:
  // A metadata block and all its sub-blocks, which follow it depth first; each sub-block
  // starts with its name. Counted, not recursed into: the nesting costs no stack.
  bool SkipMetadata() {
    uint64_t pending = 1;
    for (bool top = true; pending > 0; top = false) {
      --pending;
      if (!top && !SkipBytes(Byte())) return false;  // the sub-block's name
      const std::optional<uint32_t> entries = Varint();
      if (!entries) return false;
      for (uint32_t i = 0; i < *entries; ++i) {
        if (!SkipBytes(Byte())) return false;  // the entry's name
        const std::optional<uint32_t> size = Varint();
        if (!size || *size == 0 || !SkipBytes(*size)) return false;
      }
      const std::optional<uint32_t> subs = Varint();
      // Every sub-block takes at least three bytes (name length and two counts).
      if (!subs || *subs > Remaining() / 3) return false;
      pending += *subs;
    }
    return true;
  }

  // The bytes of one value of Draco's DataType `type` (draco/core/draco_types.h: DT_INVALID,
  // INT8, UINT8, INT16, UINT16, INT32, UINT32, INT64, UINT64, FLOAT32, FLOAT64, BOOL); 0 for
  // DT_INVALID and unknown types.
  static int DataTypeBytes(uint32_t type) {
    constexpr int kBytes[] = {0, 1, 1, 2, 2, 4, 4, 8, 8, 4, 8, 1};
    return type < std::size(kBytes) ? kBytes[type] : 0;
  }

  size_t Remaining() const { return bytes_.size() - at_; }

  // The next byte, or nullopt at the end.
  std::optional<uint32_t> Byte() {
    if (at_ >= bytes_.size()) return std::nullopt;
    return static_cast<uint8_t>(bytes_[at_++]);
  }

  std::optional<uint32_t> Uint32() {
    if (Remaining() < 4) return std::nullopt;
    const auto v = static_cast<uint32_t>(
        DecodeScalar(bytes_.data() + at_, ScalarType::kUint32, ByteOrder::kLittleEndian));
    at_ += 4;
    return v;
  }

  bool SkipBytes(std::optional<uint32_t> count) {
    if (!count || *count > Remaining()) return false;
    at_ += *count;
    return true;
  }

  // Draco's unsigned varint: 7 bits per byte, least significant first, high bit = more;
  // bits past 32 are dropped as Draco's uint32 shifts drop them.
  std::optional<uint32_t> Varint() {
    uint32_t value = 0;
    for (int i = 0; i < kMaxVarintBytes; ++i) {
      const std::optional<uint32_t> byte = Byte();
      if (!byte) return std::nullopt;
      value |= (*byte & 0x7f) << (7 * i);
      if ((*byte & 0x80) == 0) return value;
    }
    return std::nullopt;
  }

  absl::string_view bytes_;
  size_t at_;
};

}  // namespace

absl::Status CheckDracoPointCloudHeader(absl::string_view bytes) {
  if (bytes.size() < kDracoHeaderBytes) return absl::OkStatus();
  const auto flags = static_cast<uint16_t>(DecodeScalar(
      bytes.data() + kDracoFlagsOffset, ScalarType::kUint16, ByteOrder::kLittleEndian));
  HeaderWalker walker(bytes, kDracoHeaderBytes);
  if ((flags & kDracoMetadataFlag) != 0 && !walker.SkipGeometryMetadata()) {
    return absl::InvalidArgumentError(
        "the Draco metadata is malformed or runs past the end of the data");
  }
  const std::optional<int32_t> count = walker.PointCount();
  if (!count || *count <= 0) return absl::OkStatus();
  const auto points = static_cast<uint64_t>(*count);
  if (points > kMaxDracoPointsPerByte * bytes.size()) {
    return absl::InvalidArgumentError(absl::StrCat(
        "the Draco header declares ", points, " points, more than ", kMaxDracoPointsPerByte,
        " per byte of its ", bytes.size(),
        " bytes: the data is corrupt (or its points are massively duplicated)"));
  }
  // The point-cloud coders (sequential, kd-tree) describe their attributes next; Draco
  // allocates each for every point before decoding any.
  const bool point_cloud = bytes[kDracoTypeOffset] == 0 &&
                           (bytes[kDracoTypeOffset + 1] == 0 || bytes[kDracoTypeOffset + 1] == 1);
  if (!point_cloud) return absl::OkStatus();
  const std::optional<uint64_t> per_point =
      walker.DecodedBytesPerPoint(static_cast<uint8_t>(bytes[kDracoVersionOffset]),
                                  static_cast<uint8_t>(bytes[kDracoVersionOffset + 1]));
  if (!per_point) return absl::OkStatus();
  const uint64_t budget = kMaxDracoPointsPerByte * kPositionBytes * bytes.size();
  if (*per_point > 0 && points > budget / *per_point) {
    return absl::InvalidArgumentError(absl::StrCat(
        "the Draco header declares ", points, " points of ", *per_point,
        " bytes each in its attributes, more than ", kMaxDracoPointsPerByte * kPositionBytes,
        " decoded bytes per byte of its ", bytes.size(), " bytes: the data is corrupt"));
  }
  return absl::OkStatus();
}

}  // namespace membrane
