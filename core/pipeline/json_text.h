// Pieces of JSON text for the statistics and report writers. We write a few fixed
// objects, so string building beats pulling in a JSON library.
#ifndef MEMBRANE_CORE_PIPELINE_JSON_TEXT_H_
#define MEMBRANE_CORE_PIPELINE_JSON_TEXT_H_

#include <string>

#include "absl/strings/string_view.h"

namespace membrane {

// `value` as a JSON number with 9 significant digits; null for NaN and infinities, which
// JSON cannot hold (a reader then sees a missing value, not a parse error).
std::string JsonNumber(double value);

// "true" or "false".
const char* JsonBool(bool value);

// `text` as a quoted JSON string: quotes, backslashes and control characters escaped; bytes
// >= 0x80 are copied as they are (paths are UTF-8 on the systems we run on).
std::string JsonString(absl::string_view text);

}  // namespace membrane

#endif  // MEMBRANE_CORE_PIPELINE_JSON_TEXT_H_
