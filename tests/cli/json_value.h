// A small JSON reader for the tests: enough to check the statistics JSON and `check --json`
// key by key and type by type, without a JSON library in the project.
#ifndef MEMBRANE_TESTS_CLI_JSON_VALUE_H_
#define MEMBRANE_TESTS_CLI_JSON_VALUE_H_

#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace membrane::testing {

struct JsonValue {
  enum class Type { kNull, kBool, kNumber, kString, kArray, kObject };
  Type type = Type::kNull;
  bool boolean = false;
  double number = 0;
  bool integer = false;  // a number written without fraction or exponent
  std::string string;
  std::vector<JsonValue> array;
  std::map<std::string, JsonValue> object;

  // The member `key` of an object; nullptr when absent or when this is not an object.
  const JsonValue* Find(const std::string& key) const;
};

// The JSON value in `text` (surrounding whitespace allowed); nullopt on any syntax error or
// trailing text. Strings support the escapes \" \\ \/ \b \f \n \r \t (\u is kept verbatim).
std::optional<JsonValue> ParseJson(std::string_view text);

}  // namespace membrane::testing

#endif  // MEMBRANE_TESTS_CLI_JSON_VALUE_H_
