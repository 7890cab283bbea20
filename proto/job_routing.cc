#include "proto/job_routing.h"

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"

namespace membrane {

bool IsReplicaName(absl::string_view name) {
  if (name.empty() || name.size() > 63 || name.front() == '-' || name.back() == '-') return false;
  for (char c : name)
    if (!((c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '-')) return false;
  return true;
}

std::string MakeJobId(absl::string_view replica, uint64_t random) {
  const std::string hex = absl::StrFormat("%016x", random);
  return replica.empty() ? hex : absl::StrCat(replica, ".", hex);
}

absl::string_view ReplicaOfJobId(absl::string_view job_id) {
  const size_t dot = job_id.rfind('.');
  if (dot == absl::string_view::npos) return {};
  const absl::string_view replica = job_id.substr(0, dot);
  return IsReplicaName(replica) ? replica : absl::string_view();
}

}  // namespace membrane
