#include "tests/bench/open3d_mesh_peer.h"

#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "absl/status/status.h"
#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/strip.h"
#include "core/io/mesh_io.h"

namespace membrane::bench {
namespace {

// Single-quoted for /bin/sh.
std::string ShellQuote(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
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
  return absl::SimpleAtod(json.substr(begin, end - begin), &value) ? value : 0.0;
}

}  // namespace

absl::StatusOr<Open3dMeshRun> RunOpen3dPoissonMesh(const Open3dPeer& peer,
                                                   const std::string& cloud_path, int depth) {
  const char* tmpdir = std::getenv("TMPDIR");
  const std::string mesh_path =
      absl::StrCat(tmpdir != nullptr && *tmpdir != '\0' ? tmpdir : "/tmp",
                   "/bench_surface_poisson_", getpid(), ".ply");
  const std::string timeout =
      peer.timeout_seconds > 0 ? absl::StrCat("timeout ", peer.timeout_seconds, " ") : "";
  const std::string command = absl::StrCat(
      "OMP_NUM_THREADS=", peer.threads, " exec ", timeout, ShellQuote(peer.python), " ",
      ShellQuote(peer.script), " --depth ", depth, " --threads ", peer.threads,
      " --write-mesh ", ShellQuote(mesh_path), " ", ShellQuote(cloud_path));
  std::string out;
  int status = -1;
  if (FILE* pipe = popen(command.c_str(), "r"); pipe != nullptr) {
    char buffer[4096];
    size_t n;
    while ((n = fread(buffer, 1, sizeof buffer, pipe)) > 0) out.append(buffer, n);
    const int raw = pclose(pipe);
    status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  }
  auto cleanup = [&] {
    std::error_code ec;
    std::filesystem::remove(mesh_path, ec);
  };
  if (peer.timeout_seconds > 0 && status == 124) {
    cleanup();
    return absl::DeadlineExceededError(
        absl::StrCat("open3d_poisson.py did not finish in ", peer.timeout_seconds, " s"));
  }
  const size_t brace = out.rfind("\n{") != std::string::npos ? out.rfind("\n{") + 1 : out.find('{');
  if (status != 0 || brace == std::string::npos) {
    cleanup();
    return absl::InternalError(
        absl::StrCat("open3d_poisson.py exited with status ", status, ": ", out));
  }
  Open3dMeshRun result;
  Open3dRun& run = result.run;
  run.json = std::string(absl::StripAsciiWhitespace(out.substr(brace)));
  run.points = static_cast<int64_t>(JsonNumber(run.json, "points"));
  run.normals_seconds = JsonNumber(run.json, "normals_seconds");
  run.orient_seconds = JsonNumber(run.json, "orient_seconds");
  run.poisson_seconds = JsonNumber(run.json, "poisson_seconds");
  run.seconds = JsonNumber(run.json, "seconds");
  run.faces = static_cast<int64_t>(JsonNumber(run.json, "faces"));
  absl::StatusOr<TriangleMesh> mesh = ReadMesh(mesh_path);
  cleanup();
  if (!mesh.ok()) return mesh.status();
  result.mesh = std::move(*mesh);
  return result;
}

}  // namespace membrane::bench
