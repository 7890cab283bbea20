// The JSON HTTP API of membraned --http-listen, which the web console (server/web) uses: the
// same jobs, authentication and visibility as the gRPC service, over plain requests that a
// browser can make. Independent of the HTTP library (server/http_server.h carries it).
//
//   GET  /api/jobs                      {"jobs": [{"job": Job, "has_preview": bool}, ...]}
//   GET  /api/jobs/ID                   {"job": Job, "statistics": {...} | null,
//                                        "mesh": MeshSummary | null, "has_preview": bool,
//                                        "sample_points": N}
//   GET  /api/jobs/ID/events?after=N&wait=S
//                                       {"events": [JobEvent, ...], "next": M, "state": S,
//                                        "done": bool}: the stage and generation events past
//                                        the first N, waiting up to S seconds (at most
//                                        kMaxEventWaitSeconds) for one or for the job's end
//   POST /api/jobs/ID/cancel            Job, as CancelJob
//   GET  /api/jobs/ID/mesh.drc, mesh.ply   the mesh (SUCCEEDED only), converted when the job
//                                        produced the other format, within the memory budget
//                                        (429 when the conversion does not fit)
//   GET  /api/jobs/ID/preview.png       the PNG preview of the mesh (SUCCEEDED only; drawn
//                                        now for a job restored from the store without one)
//   GET  /api/jobs/ID/points            the sample of the input points: float32 x y z,
//                                        little-endian, in the mesh's positions
//
// Job, JobEvent and MeshSummary are the messages of proto/membrane/v1/reconstruction.proto in
// protobuf's JSON mapping with the proto field names (64-bit integers as strings). Errors are
// {"error": {"code": "NOT_FOUND", "message": "..."}} with 400, 401 (and WWW-Authenticate:
// Bearer), 404 (unknown, expired, or another client's job), 405, 409 (no mesh yet), 429 (a
// conversion over the memory budget).
#ifndef MEMBRANE_SERVER_HTTP_API_H_
#define MEMBRANE_SERVER_HTTP_API_H_

#include <atomic>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "absl/status/status.h"
#include "absl/strings/string_view.h"
#include "server/caller.h"
#include "server/clock.h"
#include "server/job_store.h"
#include "server/memory_budget.h"
#include "server/server_options.h"
#include "server/shared_bytes.h"

namespace membrane::server {

// The longest an events request waits for news; a browser asks again.
inline constexpr double kMaxEventWaitSeconds = 20;

struct HttpRequest {
  std::string method;  // "GET", "POST", ...
  std::string path;    // decoded, without the query
  std::string query;   // what follows '?', undecoded
  std::optional<std::string> authorization;  // the Authorization header, when sent
  std::string peer;    // for the log
};

struct HttpResponse {
  int status = 200;
  std::string content_type = "application/json";
  // The body: the shared bytes when set (a mesh, a preview, an asset: sent without a copy,
  // alive while the response is), else `body`.
  std::string body;
  std::vector<std::pair<std::string, std::string>> headers;  // beside Content-Type and -Length
  void ShareBody(std::shared_ptr<const std::string> bytes) {
    shared_bytes_ = *bytes;
    shared_owner_ = std::move(bytes);
    shared_set_ = true;
  }
  void ShareBody(SharedBytes bytes) {
    shared_bytes_ = bytes.view();
    kept_owner_ = std::move(bytes);
    shared_set_ = true;
  }
  absl::string_view Body() const { return shared_set_ ? shared_bytes_ : body; }

 private:
  bool shared_set_ = false;
  absl::string_view shared_bytes_;
  std::shared_ptr<const void> shared_owner_;
  SharedBytes kept_owner_;
};

// The JSON error response of `status` (its HTTP status from its code).
HttpResponse ErrorResponse(const absl::Status& status);

class HttpApi {
 public:
  // `options`, `store`, `clock` and `memory` (not owned) must outlive the API. `clock` times
  // the results' TTL, as for the gRPC service; a download converted to the other format
  // reserves its estimate (MeshConversionBytes) from `memory`, the jobs' budget, or is refused
  // with 429 and the numbers.
  HttpApi(const ServerOptions& options, JobStore& store, const Clock& clock,
          MemoryBudget& memory)
      : options_(options), store_(store), clock_(clock), memory_(memory) {}

  // The answer to `request`, whose path starts with "/api/". Blocks up to
  // kMaxEventWaitSeconds for an events request.
  HttpResponse Handle(const HttpRequest& request) const;

  // Ends the events requests that wait (within 250 ms) and those to come at once, for a
  // server that stops.
  void Stop() { stopping_ = true; }

 private:
  // The job `id` as `caller` may see it after dropping expired results; NotFound otherwise.
  absl::StatusOr<std::shared_ptr<Job>> FindJob(const std::string& id, const Caller& caller) const;
  HttpResponse ListJobs(const Caller& caller) const;
  HttpResponse GetJob(const Job& job) const;
  HttpResponse Events(const Job& job, const std::string& query) const;
  HttpResponse Cancel(Job& job, const Caller& caller, const HttpRequest& request) const;
  HttpResponse Download(Job& job, const std::string& file) const;

  const ServerOptions& options_;
  JobStore& store_;
  const Clock& clock_;
  MemoryBudget& memory_;
  std::atomic<bool> stopping_{false};
};

}  // namespace membrane::server

#endif  // MEMBRANE_SERVER_HTTP_API_H_
