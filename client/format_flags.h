// The format of an input or output when its name does not tell it: --input-format and
// --output-format, and standard input ("-") told by its first bytes.
#ifndef MEMBRANE_CLIENT_FORMAT_FLAGS_H_
#define MEMBRANE_CLIENT_FORMAT_FLAGS_H_

#include <optional>
#include <string>

#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "core/io/file_format.h"

namespace membrane::client {

// The format a --input-format / --output-format value names: an extension without its dot,
// any case ("ply", "xyz", "txt", "drc", ...). InvalidArgument naming `flag` and the extensions
// `use` takes when it names none of them.
absl::StatusOr<FileFormat> ParseFormatName(absl::string_view flag, absl::string_view name,
                                           FileUse use);

// What the first bytes of `bytes` say about its format: PLY ("ply" line), Draco ("DRACO"), OFF
// ("OFF", "COFF", "NOFF", "CNOFF" line), PCD (a "# .PCD" or "VERSION" line), then by the first
// line that is neither blank nor a '#' comment: OBJ (a "v", "o", "g", "mtllib" line) or XYZ
// (a number). nullopt for anything else (STL, binary noise).
std::optional<FileFormat> SniffFormat(absl::string_view bytes);

// The format of the input `path` for `use`: the one `format_flag` (--input-format) names when
// it is not empty; for "-" (standard input) what SniffFormat tells from `bytes`, which must be
// what was read; else the extension's (FormatFromPath). InvalidArgument as ParseFormatName,
// as FormatFromPath, and "stdin: ..." asking for --input-format when the bytes do not tell.
absl::StatusOr<FileFormat> InputFormat(const std::string& path, absl::string_view format_flag,
                                       FileUse use, absl::string_view bytes = "");

// The format of the output `path` for `use`: the one `format_flag` (--output-format) names when
// it is not empty; PLY for "-" (standard output); else the extension's (FormatFromPath).
absl::StatusOr<FileFormat> OutputFormat(const std::string& path, absl::string_view format_flag,
                                        FileUse use);

}  // namespace membrane::client

#endif  // MEMBRANE_CLIENT_FORMAT_FLAGS_H_
