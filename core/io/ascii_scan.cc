#include "core/io/ascii_scan.h"

#include <charconv>
#include <limits>
#include <system_error>

namespace membrane {
namespace {

bool IsAsciiSpace(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\v' || c == '\f';
}

// from_chars rejects a leading '+', which writers of all these formats emit.
absl::string_view StripPlus(absl::string_view token) {
  if (token.size() > 1 && token[0] == '+' && token[1] != '-' && token[1] != '+') {
    token.remove_prefix(1);
  }
  return token;
}

}  // namespace

bool LineScanner::Next(absl::string_view* line) {
  if (position_ >= text_.size()) return false;
  line_start_ = position_;
  ++line_number_;
  size_t end = text_.find('\n', position_);
  if (end == absl::string_view::npos) {
    end = text_.size();
    position_ = end;
  } else {
    position_ = end + 1;
  }
  absl::string_view result = text_.substr(line_start_, end - line_start_);
  if (!result.empty() && result.back() == '\r') result.remove_suffix(1);
  *line = result;
  return true;
}

bool TokenScanner::IsSeparator(char c) const {
  return IsAsciiSpace(c) || extra_separators_.find(c) != absl::string_view::npos;
}

bool TokenScanner::Next(absl::string_view* token) {
  while (position_ < text_.size() && IsSeparator(text_[position_])) ++position_;
  token_start_ = position_;
  if (position_ >= text_.size()) return false;
  while (position_ < text_.size() && !IsSeparator(text_[position_])) ++position_;
  *token = text_.substr(token_start_, position_ - token_start_);
  return true;
}

std::optional<double> ParseDouble(absl::string_view token) {
  token = StripPlus(token);
  if (token.empty()) return std::nullopt;
  double value = 0;
  const char* end = token.data() + token.size();
  const std::from_chars_result result = std::from_chars(token.data(), end, value);
  if (result.ptr != end) return std::nullopt;
  if (result.ec == std::errc::result_out_of_range) {
    // from_chars leaves `value` untouched here; the sign of the exponent tells overflow
    // from underflow.
    const bool negative = token[0] == '-';
    const size_t e = token.find_first_of("eE");
    const bool underflow =
        e != absl::string_view::npos && e + 1 < token.size() && token[e + 1] == '-';
    if (underflow) return negative ? -0.0 : 0.0;
    const double inf = std::numeric_limits<double>::infinity();
    return negative ? -inf : inf;
  }
  if (result.ec != std::errc()) return std::nullopt;
  return value;
}

std::optional<uint64_t> ParseUint64(absl::string_view token) {
  token = StripPlus(token);
  if (token.empty() || token[0] == '-') return std::nullopt;
  uint64_t value = 0;
  const char* end = token.data() + token.size();
  const std::from_chars_result result = std::from_chars(token.data(), end, value);
  if (result.ec != std::errc() || result.ptr != end) return std::nullopt;
  return value;
}

std::optional<int64_t> ParseInt64(absl::string_view token) {
  token = StripPlus(token);
  if (token.empty()) return std::nullopt;
  int64_t value = 0;
  const char* end = token.data() + token.size();
  const std::from_chars_result result = std::from_chars(token.data(), end, value);
  if (result.ec != std::errc() || result.ptr != end) return std::nullopt;
  return value;
}

}  // namespace membrane
