// server_bench: one 1,000,000-point cloud reconstructed by `membrane reconstruct --local` and
// through a membraned on loopback (`--server`), wall time of the client each way (target:
// server within 10% of local), upload and download bytes with the Draco ratio against raw
// float32, and the per-stage seconds of both statistics JSONs.
// Usage: server_bench [--points N] [--quantization BITS] [--repeat R]; run from the build tree
// (the binaries are found at ../../client/membrane and ../../server/membraned beside it).
// The R local and R server runs alternate (local, server, local, ...) so that a noisy shared
// machine slows both alike; the medians and their ratio are printed.
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "tests/bench/bench_util.h"

namespace {

namespace fs = std::filesystem;

// Starts `argv` with stdout and stderr to `log`; returns its pid.
pid_t Spawn(const std::vector<std::string>& argv, const std::string& log) {
  std::fflush(stdout);  // else the child's freopen writes our buffered lines a second time
  const pid_t pid = fork();
  if (pid == 0) {
    // One file, one offset: stderr shares stdout's descriptor.
    if (!freopen(log.c_str(), "w", stdout) || dup2(STDOUT_FILENO, STDERR_FILENO) < 0) _exit(127);
    std::vector<char*> args;
    for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    execv(args[0], args.data());
    _exit(127);
  }
  return pid;
}

int Wait(pid_t pid) {
  int status = 0;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

std::string Read(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Wall seconds of one run of `argv`; -1 when it fails.
double Timed(const std::vector<std::string>& argv, const std::string& log) {
  const auto start = std::chrono::steady_clock::now();
  const int code = Wait(Spawn(argv, log));
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (code != 0) {
    std::fprintf(stderr, "server_bench: %s failed (%d):\n%s\n", argv[1].c_str(), code,
                 Read(log).c_str());
    return -1;
  }
  return seconds;
}

std::string Match(const std::string& text, const std::string& pattern) {
  std::smatch m;
  return std::regex_search(text, m, std::regex(pattern)) ? m[1].str() : "?";
}

}  // namespace

int main(int argc, char** argv) {
  std::string points = "1000000", quantization = "11";
  int repeat = 3;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (std::string(argv[i]) == "--points") points = argv[i + 1];
    if (std::string(argv[i]) == "--quantization") quantization = argv[i + 1];
    if (std::string(argv[i]) == "--repeat") repeat = std::max(1, std::atoi(argv[i + 1]));
  }
  const fs::path here = fs::canonical("/proc/self/exe").parent_path();
  const std::string membrane = (here / "../../client/membrane").string();
  const std::string membraned = (here / "../../server/membraned").string();
  const fs::path dir = fs::temp_directory_path() / ("server_bench_" + std::to_string(getpid()));
  fs::create_directories(dir);
  const std::string cloud = (dir / "torus.ply").string();
  if (Timed({membrane, "synth", "torus", "-o", cloud, "--points", points, "--density-ratio",
             "30"},
            (dir / "synth.log").string()) < 0) {
    return 1;
  }
  const std::string server_log = (dir / "membraned.log").string();
  const pid_t server = Spawn({membraned, "--listen=127.0.0.1:0", "--workers=1"}, server_log);
  std::string port;
  for (int i = 0; i < 100 && port.empty(); ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    const std::string log = Read(server_log);
    if (log.find("server_started") != std::string::npos) port = Match(log, "port=(\\d+)");
  }
  std::vector<double> locals, remotes;
  for (int r = 0; r < repeat; ++r) {
    const double local =
        Timed({membrane, "reconstruct", cloud, "-o", (dir / "local.ply").string(), "--local",
               "--stats-json", (dir / "local.json").string()},
              (dir / "local.log").string());
    const double remote =
        Timed({membrane, "reconstruct", cloud, "-o", (dir / "remote.ply").string(),
               "--server", "127.0.0.1:" + port, "--quantization", quantization, "--stats-json",
               (dir / "remote.json").string()},
              (dir / "remote.log").string());
    if (local < 0 || remote < 0) break;
    locals.push_back(local);
    remotes.push_back(remote);
    std::printf("run %d: local %.3f s, server %.3f s\n", r + 1, local, remote);
  }
  kill(server, SIGTERM);
  Wait(server);
  if (static_cast<int>(locals.size()) < repeat) return 1;
  const double local = membrane::bench::Median(locals);
  const double remote = membrane::bench::Median(remotes);
  const std::string remote_out = Read((dir / "remote.log").string());
  std::printf("points %s, upload quantization %s bits\n", points.c_str(), quantization.c_str());
  std::printf("client wall seconds, median of %d alternating runs: local %.3f, server %.3f "
              "(server/local %.3f, %+.1f%%)\n",
              repeat, local, remote, remote / local, 100.0 * (remote - local) / local);
  std::printf("upload: %s bytes Draco of %s raw float32 bytes (%s%%)\n",
              Match(remote_out, "(\\d+) bytes as Draco").c_str(),
              Match(remote_out, "of (\\d+) raw float32").c_str(),
              Match(remote_out, "as Draco \\(([0-9.]+)%").c_str());
  std::printf("download: %s bytes Draco mesh\n",
              Match(remote_out, "download (\\d+) bytes").c_str());
  for (const char* name : {"local", "remote"}) {
    const std::string json = Read((dir / (std::string(name) + ".json")).string());
    std::printf("%s seconds (last run): %s\n", name, Match(json, "\"seconds\": (\\{[^}]*\\})").c_str());
  }
  fs::remove_all(dir);
  return 0;
}
