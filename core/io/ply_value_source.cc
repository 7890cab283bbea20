#include "core/io/ply_value_source.h"

#include "absl/strings/escaping.h"
#include "absl/strings/str_cat.h"

namespace membrane {

bool PlyBinarySource::Read(ScalarType type, double* value) {
  const size_t size = ScalarSize(type);
  if (remaining() < size) return false;
  *value = DecodeScalar(data_.data() + offset_, type, order_);
  offset_ += size;
  return true;
}

bool PlyBinarySource::Skip(uint64_t count, ScalarType type) {
  if (!MayHold(count, type)) return false;
  offset_ += count * ScalarSize(type);
  return true;
}

const char* PlyBinarySource::Take(size_t bytes) {
  if (remaining() < bytes) return nullptr;
  const char* start = data_.data() + offset_;
  offset_ += bytes;
  return start;
}

bool PlyBinarySource::MayHold(uint64_t count, ScalarType type) const {
  return count <= remaining() / ScalarSize(type);
}

size_t PlyBinarySource::MinRowBytes(const PlyElement& element) const {
  size_t bytes = 0;
  for (const PlyProperty& property : element.properties) {
    bytes += ScalarSize(property.list_count_type ? *property.list_count_type : property.type);
  }
  return bytes;
}

bool PlyBinarySource::MayHoldRows(uint64_t rows, size_t min_row_bytes) const {
  return min_row_bytes == 0 || rows <= remaining() / min_row_bytes;
}

std::string PlyBinarySource::problem() const {
  return absl::StrCat("the data ends at byte ", data_.size());
}

bool PlyAsciiSource::NextToken(absl::string_view* token) {
  if (!tokens_.Next(token)) {
    failure_offset_ = size_;
    bad_token_ = {};
    return false;
  }
  offset_ = tokens_.token_offset() + token->size();
  return true;
}

bool PlyAsciiSource::Read(ScalarType /*type*/, double* value) {
  absl::string_view token;
  if (!NextToken(&token)) return false;
  std::optional<double> parsed = ParseDouble(token);
  if (!parsed) {
    failure_offset_ = tokens_.token_offset();
    bad_token_ = token;
    return false;
  }
  *value = *parsed;
  return true;
}

bool PlyAsciiSource::Skip(uint64_t count, ScalarType /*type*/) {
  absl::string_view token;
  // Terminates: every iteration consumes a token, and there are finitely many.
  for (uint64_t i = 0; i < count; ++i) {
    if (!NextToken(&token)) return false;
  }
  return true;
}

bool PlyAsciiSource::MayHold(uint64_t count, ScalarType /*type*/) const {
  // A value takes at least one character and one separator, except the very last.
  return count <= (remaining() + 1) / 2;
}

size_t PlyAsciiSource::MinRowBytes(const PlyElement& element) const {
  return 2 * element.properties.size();
}

bool PlyAsciiSource::MayHoldRows(uint64_t rows, size_t min_row_bytes) const {
  return min_row_bytes == 0 || rows <= (remaining() + 1) / min_row_bytes;
}

std::string PlyAsciiSource::problem() const {
  if (bad_token_.empty()) return "the data ends";
  constexpr size_t kShown = 32;
  return absl::StrCat("'", absl::CHexEscape(bad_token_.substr(0, kShown)),
                      bad_token_.size() > kShown ? "..." : "", "' is not a number");
}

}  // namespace membrane
