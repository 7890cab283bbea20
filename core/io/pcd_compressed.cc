#include "core/io/pcd_compressed.h"

#include <cerrno>

#include "absl/strings/str_cat.h"
#include "core/io/parse_error.h"
#include "lzf.h"

namespace membrane {
namespace {

uint32_t ReadUint32Le(const char* bytes) {
  const auto* b = reinterpret_cast<const unsigned char*>(bytes);
  return static_cast<uint32_t>(b[0]) | static_cast<uint32_t>(b[1]) << 8 |
         static_cast<uint32_t>(b[2]) << 16 | static_cast<uint32_t>(b[3]) << 24;
}

}  // namespace

absl::StatusOr<std::string> DecompressPcdBody(absl::string_view data, size_t body_offset,
                                              uint64_t points, uint64_t packed_row_bytes,
                                              absl::string_view source) {
  const size_t remaining = data.size() - body_offset;
  if (remaining < 8) {
    return ParseError(source, body_offset,
                      absl::StrCat("binary_compressed data needs an 8-byte size header; only ",
                                   remaining, " bytes follow DATA"));
  }
  const uint32_t compressed = ReadUint32Le(data.data() + body_offset);
  const uint32_t uncompressed = ReadUint32Le(data.data() + body_offset + 4);
  const size_t block = body_offset + 8;
  if (compressed > remaining - 8) {
    return ParseError(source, body_offset,
                      absl::StrCat("the compressed block claims ", compressed, " bytes but only ",
                                   remaining - 8, " follow its size header"));
  }
  // packed_row_bytes is at least 12 (x, y, z), so the division is safe, and the product is
  // formed only when it fits in 32 bits.
  const bool fits = points <= uint64_t{UINT32_MAX} / packed_row_bytes;
  if (!fits || points * packed_row_bytes != uncompressed) {
    return ParseError(
        source, body_offset + 4,
        absl::StrCat("the header declares ", uncompressed, " uncompressed bytes, but POINTS ",
                     points, " x ", packed_row_bytes,
                     " bytes per point (the fields other than '_') make ",
                     fits ? absl::StrCat(points * packed_row_bytes)
                          : std::string("more than a 32-bit size can hold")));
  }
  if (uncompressed == 0) return std::string();
  if (uncompressed > kLzfMaxExpansion * compressed) {
    return ParseError(source, body_offset + 4,
                      absl::StrCat("an uncompressed size of ", uncompressed, " bytes from ",
                                   compressed, " compressed bytes is more than LZF can expand to"));
  }
  std::string body(uncompressed, '\0');
  errno = 0;
  const unsigned int produced =
      lzf_decompress(data.data() + block, compressed, body.data(), uncompressed);
  if (produced != uncompressed) {
    // lzf_decompress returns 0 with errno E2BIG when the output would pass `uncompressed`,
    // and 0 with EINVAL for a reference before the start or a run past the input's end.
    const bool too_long = produced == 0 && errno == E2BIG;
    return ParseError(
        source, block,
        too_long       ? absl::StrCat("the LZF data decompresses to more than the ", uncompressed,
                                      " bytes its header declares")
        : produced == 0 ? std::string("the LZF data is corrupt")
                        : absl::StrCat("the LZF data decompresses to ", produced,
                                       " bytes, not the ", uncompressed, " its header declares"));
  }
  return body;
}

}  // namespace membrane
