// How file errors of the io library become exit statuses of the command.
#ifndef MEMBRANE_CLIENT_IO_ERRORS_H_
#define MEMBRANE_CLIENT_IO_ERRORS_H_

#include "absl/status/status.h"

namespace membrane::client {

// `status` with Internal turned into InvalidArgument (same message); other codes unchanged.
// The io library reports a file that exists but cannot be read or written (permissions, a
// missing directory, a full disk) as Internal; for the user it is a path to fix (exit 3), not
// a failed job (exit 5).
absl::Status FileErrorAsInvalidInput(const absl::Status& status);

}  // namespace membrane::client

#endif  // MEMBRANE_CLIENT_IO_ERRORS_H_
