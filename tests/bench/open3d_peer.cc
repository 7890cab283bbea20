#include "tests/bench/open3d_peer.h"

#include <sys/resource.h>
#include <sys/wait.h>

#include <cstdio>
#include <cstdlib>
#include <string>

#include "absl/status/status.h"
#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/strip.h"

namespace membrane::bench {
namespace {


// Runs `command` through /bin/sh; its stdout, and the exit status in `status`.
std::string Capture(const std::string& command, int& status) {
  std::string out;
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) {
    status = -1;
    return out;
  }
  char buffer[4096];
  size_t n;
  while ((n = fread(buffer, 1, sizeof buffer, pipe)) > 0) out.append(buffer, n);
  const int raw = pclose(pipe);
  status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  return out;
}

// The value after "key": in a flat JSON object of numbers (0 when absent).
double JsonNumber(const std::string& json, const std::string& key) {
  const std::string needle = absl::StrCat("\"", key, "\":");
  const size_t at = json.find(needle);
  if (at == std::string::npos) return 0.0;
  size_t begin = at + needle.size();
  while (begin < json.size() && json[begin] == ' ') ++begin;
  size_t end = begin;
  while (end < json.size() && json[end] != ',' && json[end] != '}') ++end;
  double value = 0.0;
  if (!absl::SimpleAtod(json.substr(begin, end - begin), &value)) return 0.0;
  return value;
}

double CpuSeconds(const rusage& u) {
  return u.ru_utime.tv_sec + u.ru_stime.tv_sec + 1e-6 * (u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

}  // namespace

absl::StatusOr<std::string> Open3dVersion(const Open3dPeer& peer) {
  int status = 0;
  std::string out = Capture(
      absl::StrCat(ShellQuote(peer.python),
                   " -c 'import open3d; print(open3d.__version__)' 2>/dev/null"),
      status);
  if (status != 0) {
    return absl::NotFoundError(
        absl::StrCat(peer.python, " cannot import open3d (exit status ", status, ")"));
  }
  return std::string(absl::StripAsciiWhitespace(out));
}

absl::StatusOr<Open3dRun> RunOpen3dPoisson(const Open3dPeer& peer, const std::string& cloud_path) {
  rusage before{};
  getrusage(RUSAGE_CHILDREN, &before);
  const std::string timeout =
      peer.timeout_seconds > 0 ? absl::StrCat("timeout ", peer.timeout_seconds, " ") : "";
  const std::string command = absl::StrCat(
      "OMP_NUM_THREADS=", peer.threads, " exec ", timeout, ShellQuote(peer.python), " ",
      ShellQuote(peer.script), " --threads ", peer.threads, " ", ShellQuote(cloud_path));
  int status = 0;
  const std::string out = Capture(command, status);
  rusage after{};
  getrusage(RUSAGE_CHILDREN, &after);

  if (peer.timeout_seconds > 0 && status == 124) {
    return absl::DeadlineExceededError(
        absl::StrCat("open3d_poisson.py did not finish in ", peer.timeout_seconds, " s"));
  }
  absl::StatusOr<Open3dRun> parsed = ParseOpen3dOutput(out, status);
  if (!parsed.ok()) return parsed.status();
  Open3dRun run = *std::move(parsed);
  run.cpu_seconds = CpuSeconds(after) - CpuSeconds(before);
  run.peak_rss_kb = after.ru_maxrss;
  return run;
}

std::optional<bool> ParseOpen3dFlag(const std::string& arg,
                                    const std::function<std::optional<std::string>()>& value,
                                    Open3dPeer& peer) {
  if (arg == "--python") {
    auto v = value();
    if (!v) return false;
    peer.python = *v;
    return true;
  }
  if (arg == "--open3d-threads") {
    auto v = value();
    return v && absl::SimpleAtoi(*v, &peer.threads) && peer.threads != 0;
  }
  if (arg == "--open3d-timeout") {
    auto v = value();
    return v && absl::SimpleAtoi(*v, &peer.timeout_seconds) && peer.timeout_seconds >= 0;
  }
  return std::nullopt;
}

std::string ShellQuote(const std::string& s) {
  std::string out = "'";
  for (char c : s) {
    if (c == '\'') {
      out += "'\\''";
    } else {
      out += c;
    }
  }
  return out + "'";
}

absl::StatusOr<Open3dRun> ParseOpen3dOutput(const std::string& out, int exit_status) {
  const size_t brace = out.rfind("\n{") != std::string::npos ? out.rfind("\n{") + 1 : out.find('{');
  if (exit_status != 0 || brace == std::string::npos) {
    return absl::InternalError(
        absl::StrCat("open3d_poisson.py exited with status ", exit_status, ": ", out));
  }
  Open3dRun run;
  run.json = std::string(absl::StripAsciiWhitespace(out.substr(brace)));
  run.points = static_cast<int64_t>(JsonNumber(run.json, "points"));
  run.normals_seconds = JsonNumber(run.json, "normals_seconds");
  run.orient_seconds = JsonNumber(run.json, "orient_seconds");
  run.poisson_seconds = JsonNumber(run.json, "poisson_seconds");
  run.seconds = JsonNumber(run.json, "seconds");
  run.faces = static_cast<int64_t>(JsonNumber(run.json, "faces"));
  return run;
}

}  // namespace membrane::bench
