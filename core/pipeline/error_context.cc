#include "core/pipeline/error_context.h"

#include "absl/strings/str_cat.h"

namespace membrane {

absl::Status WithErrorContext(const absl::Status& status, const ErrorContext& context) {
  switch (status.code()) {
    case absl::StatusCode::kInvalidArgument:
      return absl::InvalidArgumentError(
          absl::StrCat(context.invalid_argument_prefix, status.message()));
    case absl::StatusCode::kResourceExhausted:
      return absl::ResourceExhaustedError(
          absl::StrCat(status.message(), context.resource_exhausted_advice));
    default: return status;
  }
}

}  // namespace membrane
