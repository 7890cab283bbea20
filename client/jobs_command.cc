#include "client/jobs_command.h"

#include <cstdio>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <google/protobuf/message.h>
#include <google/protobuf/util/json_util.h>
#include <grpcpp/client_context.h>

#include "CLI/CLI.hpp"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "absl/time/clock.h"
#include "client/flag_checks.h"
#include "client/format_flags.h"
#include "client/job_event_sink.h"
#include "client/progress_printer.h"
#include "client/remote_reconstruction.h"
#include "client/report_text.h"
#include "client/rpc_errors.h"
#include "client/server_connection.h"
#include "client/std_streams.h"
#include "membrane/v1/reconstruction.grpc.pb.h"
#include "proto/job_routing.h"

namespace membrane::client {
namespace {

struct JobsFlags {
  ConnectionFlags connection;
  ServerConnection server;  // the connection's files read, before the subcommand runs
  std::string job_id;
  std::string replica;      // list: the replica to ask, behind a balancer
  std::string output;      // watch: where to write the mesh ("-": stdout)
  std::string output_format;  // watch: the mesh's format, when not the extension's
  std::string stats_json;  // watch: where to write the statistics
  double timeout = 30;     // per call; watch: for the whole job (0 = no limit)
  bool quiet = false;
  bool json = false;       // list, get, cancel: the proto's JSON mapping on stdout
};

// A one-call context with the --timeout deadline, routed to the job's replica.
std::unique_ptr<grpc::ClientContext> CallContext(const JobsFlags& flags) {
  auto context = std::make_unique<grpc::ClientContext>();
  Authorize(*context, flags.server);
  RouteToJob(*context, flags.job_id);
  if (flags.timeout > 0) {
    context->set_deadline(absl::ToChronoTime(absl::Now() + absl::Seconds(flags.timeout)));
  }
  return context;
}

std::string StateName(v1::JobState state) { return v1::JobState_Name(state); }

// `message` in the proto3 JSON mapping (field names as in the .proto, enums by name), one
// object per line, for scripts: `membrane jobs list --json | jq`.
void PrintJson(const google::protobuf::Message& message) {
  google::protobuf::util::JsonPrintOptions options;
  options.preserve_proto_field_names = true;
  std::string json;
  // Only a message with unknown Any types fails to print; ours have none.
  if (!google::protobuf::util::MessageToJsonString(message, &json, options).ok()) json = "{}";
  std::printf("%s\n", json.c_str());
}

void PrintJob(const v1::Job& job) {
  std::printf("id: %s\nstate: %s\nqueue_position: %d\nstage: %s\nerror: %s\npeer: %s\n"
              "upload_bytes: %llu\nmesh_bytes: %llu\n",
              job.id().c_str(), StateName(job.state()).c_str(), job.queue_position(),
              job.stage().c_str(), job.error().message().c_str(), job.peer().c_str(),
              static_cast<unsigned long long>(job.upload_bytes()),
              static_cast<unsigned long long>(job.mesh_bytes()));
}

absl::Status RunList(const JobsFlags& flags) {
  if (!flags.replica.empty() && !IsReplicaName(flags.replica)) {
    return absl::InvalidArgumentError(absl::StrCat(
        "--replica '", flags.replica,
        "' is not a replica name (lower-case letters, digits and '-', as in membraned-0)"));
  }
  auto stub = v1::Reconstruction::NewStub(Connect(flags.server));
  v1::ListJobsResponse response;
  const std::unique_ptr<grpc::ClientContext> context = CallContext(flags);
  if (!flags.replica.empty()) context->AddMetadata(kReplicaHeader, flags.replica);
  const grpc::Status status = stub->ListJobs(context.get(), {}, &response);
  if (!status.ok()) return FromGrpcStatus(status, flags.server.address);
  if (flags.json) {
    PrintJson(response);
    return absl::OkStatus();
  }
  for (const v1::Job& job : response.jobs()) {
    std::printf("%s %s %s %llu %s\n", job.id().c_str(), StateName(job.state()).c_str(),
                job.stage().empty() ? "-" : job.stage().c_str(),
                static_cast<unsigned long long>(job.upload_bytes()), job.peer().c_str());
  }
  return absl::OkStatus();
}

absl::Status RunGet(const JobsFlags& flags, bool cancel) {
  auto stub = v1::Reconstruction::NewStub(Connect(flags.server));
  v1::Job job;
  grpc::Status status;
  if (cancel) {
    v1::CancelJobRequest request;
    request.set_job_id(flags.job_id);
    status = stub->CancelJob(CallContext(flags).get(), request, &job);
  } else {
    v1::GetJobRequest request;
    request.set_job_id(flags.job_id);
    status = stub->GetJob(CallContext(flags).get(), request, &job);
  }
  if (!status.ok()) return FromGrpcStatus(status, flags.server.address);
  if (flags.json) {
    PrintJson(job);
    return absl::OkStatus();
  }
  PrintJob(job);
  return absl::OkStatus();
}

absl::Status RunWatch(const JobsFlags& flags) {
  // The outputs are checked before the wait, which can be long, rather than after it.
  for (const auto& [flag, path] : {std::pair{"-o", &flags.output},
                                   std::pair{"--stats-json", &flags.stats_json}}) {
    if (path->empty()) continue;
    if (absl::Status s = CheckOutputPath(flag, *path); !s.ok()) return s;
  }
  if (IsStdStream(flags.output) && IsStdStream(flags.stats_json)) {
    return absl::InvalidArgumentError(
        "-o - and --stats-json - would both write to standard output; send one of them to a "
        "file");
  }
  FileFormat output_format = FileFormat::kPly;
  if (!flags.output.empty()) {
    absl::StatusOr<FileFormat> format =
        OutputFormat(flags.output, flags.output_format, FileUse::kWriteMesh);
    if (!format.ok()) return format.status();
    output_format = *format;
  }
  const absl::Time deadline =
      flags.timeout > 0 ? absl::Now() + absl::Seconds(flags.timeout) : absl::InfiniteFuture();
  absl::Status outcome;
  std::string mesh, statistics;
  std::vector<std::string> warnings;
  Origin3d origin;
  v1::MeshFormat format = v1::MESH_FORMAT_UNSPECIFIED;
  {
    ProgressPrinter progress(stderr, ProgressPrinter::StderrMode(flags.quiet));
    JobEventSink sink(progress);
    outcome = WatchUntilDone(flags.server, flags.job_id, deadline, sink);
    mesh = sink.mesh();
    statistics = sink.statistics_json();
    warnings = sink.warnings();
    origin = sink.origin();
    format = sink.mesh_format();
  }
  if (!outcome.ok()) return outcome;
  std::fputs(WarningLines(warnings).c_str(), stderr);
  if (!flags.stats_json.empty()) {
    if (absl::Status s = WriteOutputBytes(flags.stats_json, statistics); !s.ok()) return s;
  }
  if (flags.output.empty()) return absl::OkStatus();
  return WriteReceivedMesh(mesh, format, origin, flags.output, output_format);
}

// Adds `name` with its flags to `jobs`; `run` gets the parsed values.
CLI::App* AddJobsSubcommand(CLI::App& jobs, const char* name, const char* help,
                            std::shared_ptr<JobsFlags> flags, bool needs_id) {
  CLI::App* app = jobs.add_subcommand(name, help);
  AddConnectionFlags(*app, flags->connection);
  app->add_option("--timeout", flags->timeout, "seconds; 0 = no limit")->capture_default_str();
  if (needs_id) app->add_option("JOB_ID", flags->job_id, "the job's id")->required();
  return app;
}

}  // namespace

Command AddJobsCommand(CLI::App& parent) {
  CLI::App* jobs = parent.add_subcommand("jobs", "list, inspect, follow or cancel server jobs");
  jobs->require_subcommand(1);
  auto flags = std::make_shared<JobsFlags>();
  CLI::App* list = AddJobsSubcommand(*jobs, "list", "every job the server holds", flags, false);
  list->add_option("--replica", flags->replica,
                   "behind a balancer: list the jobs of this replica (e.g. membraned-0)");
  CLI::App* get = AddJobsSubcommand(*jobs, "get", "one job's state", flags, true);
  CLI::App* watch =
      AddJobsSubcommand(*jobs, "watch", "follow a job to its end (re-attach)", flags, true);
  watch->add_option("-o,--output", flags->output,
                    "write the job's mesh here (.ply .obj .stl .drc), or - for standard output");
  watch->add_option("--output-format", flags->output_format,
                    "the mesh's format when -o's name does not say it: ply obj stl drc; for - it "
                    "is otherwise binary PLY");
  watch->add_option("--stats-json", flags->stats_json,
                    "write the job's statistics here, or - for standard output");
  watch->add_flag("-q,--quiet", flags->quiet, "no progress lines on stderr");
  CLI::App* cancel = AddJobsSubcommand(*jobs, "cancel", "ask a job to stop", flags, true);
  for (CLI::App* app : {list, get, cancel}) {
    app->add_flag("--json", flags->json, "print the answer as JSON (the proto's JSON mapping)");
  }
  return Command{jobs, [=] {
                   absl::StatusOr<ServerConnection> server =
                       LoadServerConnection(flags->connection);
                   if (!server.ok()) return server.status();
                   flags->server = *std::move(server);
                   if (list->parsed()) return RunList(*flags);
                   if (get->parsed()) return RunGet(*flags, /*cancel=*/false);
                   if (watch->parsed()) return RunWatch(*flags);
                   if (cancel->parsed()) return RunGet(*flags, /*cancel=*/true);
                   return absl::InvalidArgumentError("jobs: expected list, get, watch or cancel");
                 }};
}

}  // namespace membrane::client
