// What server and clients agree on to route a call about one job to the replica holding it.
// Jobs live in the memory of the membraned replica that runs them, so behind a balancer a call
// naming a job (GetJob, WatchJob, CancelJob, and a client's re-attach) must reach that replica.
// A replica started with a name (membraned --replica) gives its jobs ids "NAME.HEX"; clients
// send NAME in the kReplicaHeader metadata of those calls; a balancer routes on that header
// (deploy/nginx/) and balances every other call.
#ifndef MEMBRANE_PROTO_JOB_ROUTING_H_
#define MEMBRANE_PROTO_JOB_ROUTING_H_

#include <cstdint>
#include <string>

#include "absl/strings/string_view.h"

namespace membrane {

// The metadata key (gRPC keys are lower case) carrying the replica of the job a call names.
inline constexpr char kReplicaHeader[] = "membrane-replica";

// True for a DNS label of lower-case letters, digits and '-' (1 to 63 of them, a letter or
// digit at each end): a name a balancer can put into a host name, and one with no '.', so that
// the job id's last '.' ends it.
bool IsReplicaName(absl::string_view name);

// The id of a job of `replica` (empty: no replica) whose random part is `random`:
// "replica.%016x", or "%016x" alone.
std::string MakeJobId(absl::string_view replica, uint64_t random);

// The replica named by `job_id`: what precedes its last '.' when that is a replica name; ""
// otherwise (an id of an unnamed replica, or text that is no id of ours).
absl::string_view ReplicaOfJobId(absl::string_view job_id);

}  // namespace membrane

#endif  // MEMBRANE_PROTO_JOB_ROUTING_H_
