#include "proto/endpoint_address.h"

#include <algorithm>
#include <cstdint>

#include "absl/strings/ascii.h"
#include "absl/strings/match.h"
#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/strip.h"

namespace membrane {
namespace {

absl::Status Bad(absl::string_view flag, absl::string_view address, absl::string_view why) {
  return absl::InvalidArgumentError(absl::StrCat(flag, " '", address, "': ", why));
}

}  // namespace

absl::Status CheckEndpointAddress(absl::string_view flag, absl::string_view address,
                                  PortZero port_zero) {
  if (absl::StartsWith(address, "unix:") || absl::StartsWith(address, "unix-abstract:")) {
    if (address.substr(address.find(':') + 1).empty()) {
      return Bad(flag, address, "the unix socket has no path");
    }
    return absl::OkStatus();
  }
  absl::string_view host_port = address;
  absl::ConsumePrefix(&host_port, "dns:///");
  const size_t colon = host_port.rfind(':');
  if (colon == absl::string_view::npos) {
    return Bad(flag, address, "no port; expected HOST:PORT, such as 127.0.0.1:50051");
  }
  const absl::string_view host = host_port.substr(0, colon);
  const absl::string_view port_text = host_port.substr(colon + 1);
  if (host.empty()) return Bad(flag, address, "no host; expected HOST:PORT");
  if (host.front() == '[') {
    if (host.back() != ']' || host.size() < 3) {
      return Bad(flag, address, "an IPv6 host is written in brackets, such as [::1]:50051");
    }
  } else if (absl::StrContains(host, ':')) {
    return Bad(flag, address, "an IPv6 host is written in brackets, such as [::1]:50051");
  }
  uint32_t port = 0;
  const bool digits = !port_text.empty() && port_text.size() <= 5 &&
                      std::all_of(port_text.begin(), port_text.end(), absl::ascii_isdigit);
  if (!digits || !absl::SimpleAtoi(port_text, &port) || port > 65535) {
    return Bad(flag, address, absl::StrCat("port '", port_text, "' is not a number in ",
                                           port_zero == PortZero::kAllowed ? "0" : "1",
                                           "..65535"));
  }
  if (port == 0 && port_zero == PortZero::kRefused) {
    return Bad(flag, address, "port 0 is no server's port; expected 1..65535");
  }
  return absl::OkStatus();
}

}  // namespace membrane
