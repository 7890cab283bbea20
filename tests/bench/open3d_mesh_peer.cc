#include "tests/bench/open3d_mesh_peer.h"

#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "absl/status/status.h"
#include "absl/strings/str_cat.h"
#include "core/io/mesh_io.h"

namespace membrane::bench {

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
  absl::StatusOr<Open3dRun> parsed = ParseOpen3dOutput(out, status);
  if (!parsed.ok()) {
    cleanup();
    return parsed.status();
  }
  Open3dMeshRun result;
  result.run = *std::move(parsed);
  absl::StatusOr<TriangleMesh> mesh = ReadMesh(mesh_path);
  cleanup();
  if (!mesh.ok()) return mesh.status();
  result.mesh = std::move(*mesh);
  return result;
}

}  // namespace membrane::bench
