// The HOST:PORT addresses that membraned listens on and clients connect to. gRPC takes any
// string as a target and resolves it late: "127.0.0.1:99999" reaches port 34463 (99999 mod
// 65536) and a missing port falls back to 443. Both ends check an address here first so that
// a typo is one clear error before anything is started or sent.
#ifndef MEMBRANE_PROTO_ENDPOINT_ADDRESS_H_
#define MEMBRANE_PROTO_ENDPOINT_ADDRESS_H_

#include "absl/status/status.h"
#include "absl/strings/string_view.h"

namespace membrane {

// Whether port 0 ("any free port") is allowed: yes for an address to listen on, no for one to
// connect to.
enum class PortZero { kAllowed, kRefused };

// OK when `address` is HOST:PORT with a non-empty host (a name, an IPv4 address or a bracketed
// IPv6 address such as [::1]) and a decimal port in 1..65535 (0..65535 with PortZero::kAllowed),
// optionally after the "dns:///" scheme, or a "unix:" / "unix-abstract:" socket path.
// INVALID_ARGUMENT naming `flag`, the address and what is wrong otherwise.
absl::Status CheckEndpointAddress(absl::string_view flag, absl::string_view address,
                                  PortZero port_zero);

}  // namespace membrane

#endif  // MEMBRANE_PROTO_ENDPOINT_ADDRESS_H_
