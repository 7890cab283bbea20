#include "server/http_api.h"

#include <algorithm>
#include <cstdint>
#include <utility>

#include <google/protobuf/util/json_util.h>

#include "absl/strings/match.h"
#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_split.h"
#include "absl/strings/strip.h"
#include "server/bearer_token.h"
#include "server/client_text.h"
#include "server/memory_release.h"
#include "server/mesh_download.h"
#include "server/preview_sink.h"
#include "server/server_log.h"

namespace membrane::server {
namespace {

int HttpStatusOf(absl::StatusCode code) {
  switch (code) {
    case absl::StatusCode::kOk: return 200;
    case absl::StatusCode::kInvalidArgument: return 400;
    case absl::StatusCode::kUnauthenticated: return 401;
    case absl::StatusCode::kPermissionDenied: return 403;
    case absl::StatusCode::kNotFound: return 404;
    case absl::StatusCode::kUnimplemented: return 405;  // a method the path does not take
    case absl::StatusCode::kFailedPrecondition: return 409;
    case absl::StatusCode::kResourceExhausted: return 429;
    case absl::StatusCode::kUnavailable: return 503;
    default: return 500;
  }
}

// `message` in protobuf's JSON mapping, with the proto field names and every field present.
std::string ToJson(const google::protobuf::Message& message) {
  google::protobuf::util::JsonPrintOptions options;
  options.always_print_primitive_fields = true;
  options.preserve_proto_field_names = true;
  std::string json;
  // Only fails for messages with Any fields whose types are unknown; ours have none.
  if (!google::protobuf::util::MessageToJsonString(message, &json, options).ok()) return "null";
  return json;
}

// `text` as a JSON string literal.
std::string JsonString(absl::string_view text) {
  std::string out = "\"";
  for (const char c : text) {
    const auto u = static_cast<unsigned char>(c);
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (u < 0x20) {
      absl::StrAppend(&out, "\\u00", absl::Hex(u, absl::kZeroPad2));
    } else {
      out += c;
    }
  }
  return out + "\"";
}

HttpResponse JsonResponse(std::string json) {
  HttpResponse response;
  response.body = std::move(json);
  // Job states change: a cached answer would show the past.
  response.headers.push_back({"Cache-Control", "no-store"});
  return response;
}

HttpResponse BytesResponse(SharedBytes bytes, std::string content_type) {
  HttpResponse response;
  response.content_type = std::move(content_type);
  response.ShareBody(std::move(bytes));
  response.headers.push_back({"Cache-Control", "no-store"});
  return response;
}

// The value of `key` in `query` ("a=1&b=2"), or nullopt.
std::optional<std::string> QueryValue(const std::string& query, absl::string_view key) {
  for (absl::string_view pair : absl::StrSplit(query, '&')) {
    std::pair<absl::string_view, absl::string_view> kv = absl::StrSplit(pair, absl::MaxSplits('=', 1));
    if (kv.first == key) return std::string(kv.second);
  }
  return std::nullopt;
}

// Whether preview.png answers: every SUCCEEDED job has one, or gets it when first asked.
bool HasPreview(const Job& job) { return job.state() == v1::SUCCEEDED; }

}  // namespace

HttpResponse ErrorResponse(const absl::Status& status) {
  HttpResponse response;
  response.status = HttpStatusOf(status.code());
  response.body = absl::StrCat("{\"error\":{\"code\":",
                               JsonString(absl::StatusCodeToString(status.code())),
                               ",\"message\":", JsonString(status.message()), "}}");
  if (status.code() == absl::StatusCode::kUnauthenticated) {
    response.headers.push_back({"WWW-Authenticate", "Bearer"});
  }
  response.headers.push_back({"Cache-Control", "no-store"});
  return response;
}

absl::StatusOr<std::shared_ptr<Job>> HttpApi::FindJob(const std::string& id,
                                                      const Caller& caller) const {
  // Expiry is lazy, as for the gRPC calls: every lookup first drops the results past their time.
  if (store_.RemoveFinishedBefore(clock_.Now() - absl::Seconds(options_.result_ttl_seconds)) > 0) {
    ReleaseFreedMemory();
  }
  std::shared_ptr<Job> job = store_.Find(id);
  // Another client's job is answered as an unknown one: its existence is not theirs to learn.
  if (job == nullptr || !caller.Sees(*job)) {
    return absl::NotFoundError(
        absl::StrCat("no job '", ClientText(id), "' (unknown, or its result expired)"));
  }
  return job;
}

HttpResponse HttpApi::Handle(const HttpRequest& request) const {
  absl::StatusOr<const ClientToken*> client =
      CheckAuthorization(request.authorization, options_.clients);
  if (!client.ok()) {
    LogEvent("http_unauthenticated",
             {{"peer", request.peer}, {"message", std::string(client.status().message())}});
    return ErrorResponse(client.status());
  }
  const Caller caller = CallerOf(*client);
  absl::string_view rest = request.path;
  if (!absl::ConsumePrefix(&rest, "/api/jobs")) {
    return ErrorResponse(absl::NotFoundError(
        absl::StrCat("no API path '", ClientText(request.path), "' (see /api/jobs)")));
  }
  const auto only = [&](absl::string_view method) -> std::optional<HttpResponse> {
    if (request.method == method) return std::nullopt;
    HttpResponse response = ErrorResponse(absl::UnimplementedError(
        absl::StrCat(ClientText(request.path), " takes ", method, ", not ",
                     ClientText(request.method))));
    response.headers.push_back({"Allow", std::string(method)});
    return response;
  };
  if (rest.empty() || rest == "/") {
    if (auto refused = only("GET")) return *refused;
    if (store_.RemoveFinishedBefore(clock_.Now() - absl::Seconds(options_.result_ttl_seconds)) >
        0) {
      ReleaseFreedMemory();
    }
    return ListJobs(caller);
  }
  if (!absl::ConsumePrefix(&rest, "/")) {
    return ErrorResponse(absl::NotFoundError(
        absl::StrCat("no API path '", ClientText(request.path), "' (see /api/jobs)")));
  }
  const std::pair<std::string, std::string> id_and_what =
      absl::StrSplit(rest, absl::MaxSplits('/', 1));
  absl::StatusOr<std::shared_ptr<Job>> job = FindJob(id_and_what.first, caller);
  if (!job.ok()) return ErrorResponse(job.status());
  const std::string& what = id_and_what.second;
  if (what.empty()) {
    if (auto refused = only("GET")) return *refused;
    return GetJob(**job);
  }
  if (what == "events") {
    if (auto refused = only("GET")) return *refused;
    return Events(**job, request.query);
  }
  if (what == "cancel") {
    if (auto refused = only("POST")) return *refused;
    return Cancel(**job, caller, request);
  }
  if (what == "mesh.drc" || what == "mesh.ply" || what == "preview.png" || what == "points") {
    if (auto refused = only("GET")) return *refused;
    return Download(**job, what);
  }
  return ErrorResponse(absl::NotFoundError(
      absl::StrCat("no API path '", ClientText(request.path),
                   "' (a job has events, cancel, mesh.drc, mesh.ply, preview.png, points)")));
}

HttpResponse HttpApi::ListJobs(const Caller& caller) const {
  std::string json = "{\"jobs\":[";
  bool first = true;
  for (const std::shared_ptr<Job>& job : store_.List()) {
    if (!caller.Sees(*job)) continue;
    absl::StrAppend(&json, first ? "" : ",", "{\"job\":", ToJson(job->Snapshot()),
                    ",\"has_preview\":", HasPreview(*job) ? "true" : "false", "}");
    first = false;
  }
  json += "]}";
  return JsonResponse(std::move(json));
}

HttpResponse HttpApi::GetJob(const Job& job) const {
  const v1::Job snapshot = job.Snapshot();
  std::string statistics = "null", mesh = "null";
  if (std::optional<Job::Outcome> outcome = job.Closing();
      outcome.has_value() && outcome->result.has_value()) {
    statistics = outcome->result->result().statistics_json();
    mesh = ToJson(outcome->result->result().mesh());
  }
  return JsonResponse(absl::StrCat(
      "{\"job\":", ToJson(snapshot), ",\"statistics\":", statistics, ",\"mesh\":", mesh,
      ",\"has_preview\":", HasPreview(job) ? "true" : "false",
      ",\"sample_points\":", job.point_sample().size() / (3 * sizeof(float)), "}"));
}

HttpResponse HttpApi::Events(const Job& job, const std::string& query) const {
  int64_t after = 0;
  double wait = 0;
  if (std::optional<std::string> v = QueryValue(query, "after");
      v.has_value() && (!absl::SimpleAtoi(*v, &after) || after < 0)) {
    return ErrorResponse(absl::InvalidArgumentError(
        absl::StrCat("after='", ClientText(*v), "' is not an event count (an integer >= 0)")));
  }
  if (std::optional<std::string> v = QueryValue(query, "wait");
      v.has_value() && (!absl::SimpleAtod(*v, &wait) || !(wait >= 0))) {
    return ErrorResponse(absl::InvalidArgumentError(
        absl::StrCat("wait='", ClientText(*v), "' is not a number of seconds >= 0")));
  }
  std::vector<v1::JobEvent> events;
  // Waited in slices, so that a stopping server is not held by its open requests.
  const absl::Time end = absl::Now() + absl::Seconds(std::min(wait, kMaxEventWaitSeconds));
  size_t next = static_cast<size_t>(after);
  do {
    next = job.WaitForEvents(static_cast<size_t>(after),
                             std::min(end - absl::Now(), absl::Milliseconds(250)), events);
  } while (events.empty() && !job.closed() && !stopping_ && absl::Now() < end);
  const v1::Job snapshot = job.Snapshot();
  std::string json = "{\"events\":[";
  for (size_t i = 0; i < events.size(); ++i) {
    absl::StrAppend(&json, i == 0 ? "" : ",", ToJson(events[i]));
  }
  absl::StrAppend(&json, "],\"next\":", next, ",\"state\":",
                  JsonString(v1::JobState_Name(snapshot.state())),
                  ",\"done\":", job.closed() ? "true" : "false", "}");
  return JsonResponse(std::move(json));
}

HttpResponse HttpApi::Cancel(Job& job, const Caller& caller, const HttpRequest& request) const {
  job.RequestCancel(caller.CancelReason(job));
  LogEvent("job_cancel_requested",
           {{"job", job.id()}, {"peer", request.peer}, {"client", caller.LogName()}});
  return JsonResponse(ToJson(job.Snapshot()));
}

HttpResponse HttpApi::Download(Job& job, const std::string& file) const {
  if (file == "preview.png" && job.preview_png().empty()) {
    // A job restored from the store has its mesh but no preview: drawn once, then kept.
    if (std::optional<Job::Outcome> outcome = job.Closing();
        outcome.has_value() && !outcome->mesh.empty()) {
      absl::StatusOr<TriangleMesh> mesh = ResultMesh(outcome->mesh.view(), job.parameters());
      if (!mesh.ok()) return ErrorResponse(absl::InternalError(mesh.status().message()));
      absl::StatusOr<std::string> png = PreviewPng(*mesh);
      if (!png.ok()) return ErrorResponse(png.status());
      job.SetPreview(*std::move(png));
    }
  }
  if (file == "preview.png" || file == "points") {
    SharedBytes bytes = file == "points" ? job.point_sample() : job.preview_png();
    if (bytes.empty()) {
      return ErrorResponse(absl::FailedPreconditionError(
          absl::StrCat("job '", job.id(), "' has no ", file == "points" ? "point sample" : "preview",
                       " (", v1::JobState_Name(job.state()), ")")));
    }
    return BytesResponse(std::move(bytes),
                         file == "points" ? "application/octet-stream" : "image/png");
  }
  std::optional<Job::Outcome> outcome = job.Closing();
  if (!outcome.has_value() || outcome->mesh.empty()) {
    return ErrorResponse(absl::FailedPreconditionError(absl::StrCat(
        "job '", job.id(), "' has no mesh (", v1::JobState_Name(job.state()), ")")));
  }
  const v1::MeshFormat format = file == "mesh.ply" ? v1::MESH_FORMAT_PLY : v1::MESH_FORMAT_DRACO;
  HttpResponse response;
  const bool same = (format == v1::MESH_FORMAT_PLY) ==
                    (job.parameters().mesh_format() == v1::MESH_FORMAT_PLY);
  if (same) {
    response = BytesResponse(outcome->mesh, "application/octet-stream");
  } else {
    // The conversion holds a decoded mesh and its new bytes: memory the jobs' budget covers.
    const v1::MeshSummary summary =
        outcome->result.has_value() ? outcome->result->result().mesh() : v1::MeshSummary();
    MemoryBudget::Share share(memory_);
    if (absl::Status s = share.TryAdd(MeshConversionBytes(summary.vertices(), summary.faces()),
                                      absl::StrCat("converting job '", job.id(), "''s mesh to ",
                                                   file == "mesh.ply" ? "PLY" : "Draco"));
        !s.ok()) {
      return ErrorResponse(s);
    }
    absl::StatusOr<std::string> converted =
        MeshInFormat(outcome->mesh.view(), job.parameters(), format);
    if (!converted.ok()) return ErrorResponse(absl::InternalError(converted.status().message()));
    response.content_type = "application/octet-stream";
    response.body = *std::move(converted);
    response.headers.push_back({"Cache-Control", "no-store"});
  }
  response.headers.push_back(
      {"Content-Disposition",
       absl::StrCat("attachment; filename=\"", job.id(), file == "mesh.ply" ? ".ply" : ".drc",
                    "\"")});
  return response;
}

}  // namespace membrane::server
