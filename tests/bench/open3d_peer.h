// Runs the peer, Open3D screened Poisson (tests/bench/open3d_poisson.py), on a cloud file.
#ifndef MEMBRANE_TESTS_BENCH_OPEN3D_PEER_H_
#define MEMBRANE_TESTS_BENCH_OPEN3D_PEER_H_

#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include "absl/status/statusor.h"

namespace membrane::bench {

struct Open3dPeer {
  std::string python = "/usr/bin/python3";  // Debian's, which has python3-open3d
  std::string script;                         // path of open3d_poisson.py
  int threads = 1;                            // OMP_NUM_THREADS and Poisson n_threads
  int timeout_seconds = 0;                    // > 0: stop the script after this long
};

// The Open3D version when `peer.python` imports open3d; otherwise an error whose message
// says why (interpreter missing, import failed).
absl::StatusOr<std::string> Open3dVersion(const Open3dPeer& peer);

// Parses a flag of the peer that every benchmark running it takes (--python,
// --open3d-threads, --open3d-timeout), reading its value with `value` (nullopt when missing).
// nullopt when `arg` is none of them; otherwise whether its value was valid.
std::optional<bool> ParseOpen3dFlag(const std::string& arg,
                                    const std::function<std::optional<std::string>()>& value,
                                    Open3dPeer& peer);

struct Open3dRun {
  int64_t points = 0;
  double normals_seconds = 0.0;  // estimate_normals, KNN 30
  double orient_seconds = 0.0;   // orient_normals_consistent_tangent_plane(30)
  double poisson_seconds = 0.0;  // depth 9
  double seconds = 0.0;          // wall: the three above
  double cpu_seconds = 0.0;      // user + system of the python process, reading included
  int64_t faces = 0;
  int64_t peak_rss_kb = 0;       // of the python process
  std::string json;              // the script's line, as printed
};

// Single-quoted for /bin/sh: the peers build their command lines with it.
std::string ShellQuote(const std::string& s);

// The run the script reported: its last JSON line in `out` (points, the three phases' and the
// total seconds, faces). Internal with the output when `exit_status` is not 0 or no JSON line
// was printed. Resource figures (cpu_seconds, peak_rss_kb) are left to the caller.
absl::StatusOr<Open3dRun> ParseOpen3dOutput(const std::string& out, int exit_status);

// Runs the script on `cloud_path`. DeadlineExceeded when peer.timeout_seconds passed first;
// Internal with the script's output when it fails or prints no JSON line. Must be the only child process running (rusage of children is used).
absl::StatusOr<Open3dRun> RunOpen3dPoisson(const Open3dPeer& peer, const std::string& cloud_path);

}  // namespace membrane::bench

#endif  // MEMBRANE_TESTS_BENCH_OPEN3D_PEER_H_
