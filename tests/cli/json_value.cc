#include "tests/cli/json_value.h"

#include <cctype>
#include <cstdlib>
#include <utility>

namespace membrane::testing {
namespace {

class Parser {
 public:
  explicit Parser(std::string_view text) : text_(text) {}

  std::optional<JsonValue> ParseDocument() {
    std::optional<JsonValue> value = ParseValue();
    SkipSpace();
    if (!value || pos_ != text_.size()) return std::nullopt;
    return value;
  }

 private:
  void SkipSpace() {
    while (pos_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[pos_]))) ++pos_;
  }
  bool Consume(std::string_view token) {
    if (text_.substr(pos_, token.size()) != token) return false;
    pos_ += token.size();
    return true;
  }

  std::optional<JsonValue> ParseValue() {
    SkipSpace();
    if (pos_ >= text_.size()) return std::nullopt;
    JsonValue v;
    const char c = text_[pos_];
    if (c == '{') return ParseObject();
    if (c == '[') return ParseArray();
    if (c == '"') {
      std::optional<std::string> s = ParseString();
      if (!s) return std::nullopt;
      v.type = JsonValue::Type::kString;
      v.string = std::move(*s);
      return v;
    }
    if (Consume("true")) {
      v.type = JsonValue::Type::kBool;
      v.boolean = true;
      return v;
    }
    if (Consume("false")) {
      v.type = JsonValue::Type::kBool;
      return v;
    }
    if (Consume("null")) return v;
    return ParseNumber();
  }

  std::optional<JsonValue> ParseNumber() {
    const size_t start = pos_;
    if (pos_ < text_.size() && text_[pos_] == '-') ++pos_;
    bool integer = true;
    bool digits = false;
    while (pos_ < text_.size()) {
      const char c = text_[pos_];
      if (std::isdigit(static_cast<unsigned char>(c))) {
        digits = true;
      } else if (c == '.' || c == 'e' || c == 'E' || c == '+' || c == '-') {
        integer = false;
      } else {
        break;
      }
      ++pos_;
    }
    if (!digits) return std::nullopt;
    const std::string number(text_.substr(start, pos_ - start));
    char* end = nullptr;
    JsonValue v;
    v.type = JsonValue::Type::kNumber;
    v.number = std::strtod(number.c_str(), &end);
    if (end != number.c_str() + number.size()) return std::nullopt;
    v.integer = integer;
    return v;
  }

  std::optional<std::string> ParseString() {
    if (!Consume("\"")) return std::nullopt;
    std::string out;
    while (pos_ < text_.size()) {
      const char c = text_[pos_++];
      if (c == '"') return out;
      if (c != '\\') {
        out += c;
        continue;
      }
      if (pos_ >= text_.size()) return std::nullopt;
      const char e = text_[pos_++];
      switch (e) {
        case '"':
        case '\\':
        case '/': out += e; break;
        case 'b': out += '\b'; break;
        case 'f': out += '\f'; break;
        case 'n': out += '\n'; break;
        case 'r': out += '\r'; break;
        case 't': out += '\t'; break;
        case 'u': out += "\\u"; break;
        default: return std::nullopt;
      }
    }
    return std::nullopt;
  }

  std::optional<JsonValue> ParseArray() {
    JsonValue v;
    v.type = JsonValue::Type::kArray;
    Consume("[");
    SkipSpace();
    if (Consume("]")) return v;
    for (;;) {
      std::optional<JsonValue> item = ParseValue();
      if (!item) return std::nullopt;
      v.array.push_back(std::move(*item));
      SkipSpace();
      if (Consume("]")) return v;
      if (!Consume(",")) return std::nullopt;
    }
  }

  std::optional<JsonValue> ParseObject() {
    JsonValue v;
    v.type = JsonValue::Type::kObject;
    Consume("{");
    SkipSpace();
    if (Consume("}")) return v;
    for (;;) {
      SkipSpace();
      std::optional<std::string> key = ParseString();
      if (!key) return std::nullopt;
      SkipSpace();
      if (!Consume(":")) return std::nullopt;
      std::optional<JsonValue> value = ParseValue();
      if (!value) return std::nullopt;
      v.object[*key] = std::move(*value);
      SkipSpace();
      if (Consume("}")) return v;
      if (!Consume(",")) return std::nullopt;
    }
  }

  std::string_view text_;
  size_t pos_ = 0;
};

}  // namespace

const JsonValue* JsonValue::Find(const std::string& key) const {
  if (type != Type::kObject) return nullptr;
  auto it = object.find(key);
  return it == object.end() ? nullptr : &it->second;
}

std::optional<JsonValue> ParseJson(std::string_view text) { return Parser(text).ParseDocument(); }

}  // namespace membrane::testing
