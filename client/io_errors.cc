#include "client/io_errors.h"

namespace membrane::client {

absl::Status FileErrorAsInvalidInput(const absl::Status& status) {
  if (status.code() != absl::StatusCode::kInternal) return status;
  return absl::InvalidArgumentError(status.message());
}

}  // namespace membrane::client
