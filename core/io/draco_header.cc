#include "core/io/draco_header.h"

#include <cstddef>
#include <optional>

#include "absl/strings/str_cat.h"
#include "core/io/binary_scalar.h"

namespace membrane {
namespace {

constexpr size_t kDracoHeaderBytes = 11;  // "DRACO", 2 version bytes, type, method, flags
constexpr size_t kDracoFlagsOffset = 9;   // uint16, little endian
constexpr uint16_t kDracoMetadataFlag = 0x8000;
// Draco reads a uint32 varint from at most 5 bytes.
constexpr int kMaxVarintBytes = 5;

// A cursor over the bytes after the header; every read fails rather than pass the end.
class MetadataWalker {
 public:
  MetadataWalker(absl::string_view bytes, size_t at) : bytes_(bytes), at_(at) {}

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

  size_t Remaining() const { return bytes_.size() - at_; }

  // The next byte, or nullopt at the end.
  std::optional<uint32_t> Byte() {
    if (at_ >= bytes_.size()) return std::nullopt;
    return static_cast<uint8_t>(bytes_[at_++]);
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

absl::Status CheckDracoPointCount(absl::string_view bytes) {
  if (bytes.size() < kDracoHeaderBytes) return absl::OkStatus();
  const auto flags = static_cast<uint16_t>(DecodeScalar(
      bytes.data() + kDracoFlagsOffset, ScalarType::kUint16, ByteOrder::kLittleEndian));
  size_t count_at = kDracoHeaderBytes;
  if ((flags & kDracoMetadataFlag) != 0) {
    MetadataWalker walker(bytes, kDracoHeaderBytes);
    if (!walker.SkipGeometryMetadata()) {
      return absl::InvalidArgumentError(
          "the Draco metadata is malformed or runs past the end of the data");
    }
    count_at = walker.offset();
  }
  if (bytes.size() < count_at + sizeof(int32_t)) return absl::OkStatus();
  const auto count = static_cast<int64_t>(
      DecodeScalar(bytes.data() + count_at, ScalarType::kInt32, ByteOrder::kLittleEndian));
  if (count > 0 && static_cast<uint64_t>(count) > kMaxDracoPointsPerByte * bytes.size()) {
    return absl::InvalidArgumentError(absl::StrCat(
        "the Draco header declares ", count, " points, more than ", kMaxDracoPointsPerByte,
        " per byte of its ", bytes.size(),
        " bytes: the data is corrupt (or its points are massively duplicated)"));
  }
  return absl::OkStatus();
}

}  // namespace membrane
