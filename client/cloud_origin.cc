#include "client/cloud_origin.h"

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "core/io/coordinate_shift.h"
#include "core/io/file_format.h"

namespace membrane::client {

absl::Status CheckOutputKeepsOrigin(const Origin3d& origin, FileFormat format,
                                    const std::string& output_name) {
  absl::Status s = CheckOriginFitsFormat(origin, format, FileUse::kWriteMesh);
  if (s.ok()) return s;
  return absl::InvalidArgumentError(absl::StrCat(output_name, ": ", s.message()));
}

std::string OriginNote(const Origin3d& origin) {
  if (origin == Origin3d{0, 0, 0}) return "";
  // 0.0 - v, not -v: an axis left in place reads "0", not "-0".
  return absl::StrFormat(" (moved by %.17g, %.17g, %.17g for float32)", 0.0 - origin[0],
                         0.0 - origin[1], 0.0 - origin[2]);
}

}  // namespace membrane::client
