#include "core/io/decode_subprocess.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "absl/status/status.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "absl/strings/str_join.h"
#include "absl/strings/strip.h"
#include "core/io/decode_helper.h"
#include "core/io/decode_progress.h"
#include "core/io/geometry_checks.h"
#include "core/io/helper_output_reader.h"

namespace membrane {
namespace {

constexpr int kPollMillis = 50;  // how often the timeout and the cancel token are looked at
constexpr int kOutputPipeBytes = 1 << 20;

#if defined(__SANITIZE_ADDRESS__)
constexpr bool kAddressSanitizer = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
constexpr bool kAddressSanitizer = true;
#else
constexpr bool kAddressSanitizer = false;
#endif
#else
constexpr bool kAddressSanitizer = false;
#endif

// The helper's environment: ours, except in AddressSanitizer builds (the test suite's
// sanitizer job). ASan reserves terabytes of shadow address space as it starts, so a helper
// built with it dies at once under RLIMIT_AS; there the allocator's own limits stand in for
// it (one allocation, and the resident size), and leak checking is off because a leak inside
// Draco would fail every decode.
std::vector<std::string> HelperEnvironment(int64_t memory_bytes) {
  std::vector<std::string> env;
  std::string asan_options;
  for (char** e = environ; *e != nullptr; ++e) {
    const std::string entry = *e;
    if (kAddressSanitizer && entry.rfind("ASAN_OPTIONS=", 0) == 0) {
      asan_options = entry.substr(13);
    } else {
      env.push_back(entry);
    }
  }
  if (kAddressSanitizer) {
    const int64_t mb = std::max<int64_t>(1, memory_bytes >> 20);
    env.push_back(absl::StrCat("ASAN_OPTIONS=", asan_options, asan_options.empty() ? "" : ":",
                               "max_allocation_size_mb=", mb, ":hard_rss_limit_mb=", mb,
                               ":allocator_may_return_null=0:detect_leaks=0"));
  }
  return env;
}

std::string HelperName(const DecodeLimits& limits) {
  return limits.helper.empty() ? std::string("(none given)") : limits.helper.front();
}

// Pipe ends owned by the parent; closed on destruction.
struct ChildPipes {
  int to_stdin = -1;
  int from_stdout = -1;
  int from_stderr = -1;
  ~ChildPipes() {
    for (int fd : {to_stdin, from_stdout, from_stderr}) {
      if (fd >= 0) close(fd);
    }
  }
};

// Starts the helper with its limits and `options` (RunDecodeHelper's arguments after
// MAX_POINTS); fills `pipes`. Returns the child's pid or -1.
pid_t StartHelper(const DecodeLimits& limits, const std::vector<std::string>& options,
                  ChildPipes& pipes) {
  if (limits.helper.empty()) return -1;
  int in[2], out[2], err[2];
  if (pipe2(in, O_CLOEXEC) != 0) return -1;
  if (pipe2(out, O_CLOEXEC) != 0) {
    close(in[0]);
    close(in[1]);
    return -1;
  }
  if (pipe2(err, O_CLOEXEC) != 0) {
    for (int fd : {in[0], in[1], out[0], out[1]}) close(fd);
    return -1;
  }
  // The points come back through this pipe: 1 MB (Linux's default pipe-max-size) moves a
  // 10M-point cloud in 115 writes instead of 1,830 of the default 64 KB. Where the size cannot
  // be set, the default pipe works the same, in more steps.
  fcntl(out[0], F_SETPIPE_SZ, kOutputPipeBytes);
  // Everything the child needs is prepared before fork: after it, only async-signal-safe calls.
  std::vector<std::string> args = limits.helper;
  args.push_back(std::to_string(limits.max_points));
  args.insert(args.end(), options.begin(), options.end());
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  const rlim_t cpu = static_cast<rlim_t>(std::ceil(std::max(1.0, limits.timeout_seconds)));
  const rlimit cpu_limit{cpu, cpu + 1};
  const rlimit memory_limit{static_cast<rlim_t>(limits.memory_bytes),
                            static_cast<rlim_t>(limits.memory_bytes)};
  const rlimit no_core{0, 0};
  std::vector<std::string> env = HelperEnvironment(limits.memory_bytes);
  std::vector<char*> envp;
  for (std::string& e : env) envp.push_back(e.data());
  envp.push_back(nullptr);
  const pid_t parent = getpid();
  const pid_t pid = fork();
  if (pid == 0) {
    // The child dies with the thread that started it: a server killed outright (SIGKILL, the
    // OOM killer) would otherwise leave its decoders running on, under their limits but with
    // nobody to read them. A parent that died before the prctl is seen in getppid (the child
    // has been reparented), and the child leaves at once. The thread waits for the child
    // (RunHelper), so it outlives it in every other case.
    prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (getppid() != parent) _exit(127);
    dup2(in[0], STDIN_FILENO);
    dup2(out[1], STDOUT_FILENO);
    dup2(err[1], STDERR_FILENO);
    setrlimit(RLIMIT_CPU, &cpu_limit);
    if (!kAddressSanitizer) setrlimit(RLIMIT_AS, &memory_limit);
    setrlimit(RLIMIT_CORE, &no_core);
    execve(argv[0], argv.data(), envp.data());
    _exit(127);
  }
  close(in[0]);
  close(out[1]);
  close(err[1]);
  pipes.to_stdin = in[1];
  pipes.from_stdout = out[0];
  pipes.from_stderr = err[0];
  if (pid < 0) return -1;
  for (int fd : {pipes.to_stdin, pipes.from_stdout, pipes.from_stderr}) {
    fcntl(fd, F_SETFL, fcntl(fd, F_GETFL) | O_NONBLOCK);
  }
  return pid;
}

// Reads what `fd` has into `sink`; false at end of file or on error.
bool DrainText(int fd, std::string& sink) {
  char buffer[1 << 12];
  while (true) {
    const ssize_t n = read(fd, buffer, sizeof buffer);
    if (n > 0) {
      sink.append(buffer, static_cast<size_t>(n));
      continue;
    }
    if (n < 0 && (errno == EAGAIN || errno == EINTR)) return true;
    return false;
  }
}

enum class Exchange { kDone, kTimedOut, kCancelled };

// Feeds `bytes` to the child and reads its output into `out` and `err` until both output pipes
// close. Counts the child's progress on `progress` as it goes.
Exchange Communicate(absl::string_view bytes, const DecodeLimits& limits,
                     const CancelToken& cancel, ChildPipes& pipes, DecodeProgress& progress,
                     HelperOutputReader& out, std::string& err) {
  const auto deadline = std::chrono::steady_clock::now() +
                        std::chrono::duration<double>(limits.timeout_seconds);
  size_t written = 0;
  bool out_open = true, err_open = true;
  while (out_open || err_open) {
    if (cancel.cancelled()) return Exchange::kCancelled;
    if (std::chrono::steady_clock::now() > deadline) return Exchange::kTimedOut;
    pollfd fds[3] = {{pipes.from_stdout, POLLIN, 0}, {pipes.from_stderr, POLLIN, 0},
                     {pipes.to_stdin, POLLOUT, 0}};
    const nfds_t count = pipes.to_stdin >= 0 ? 3 : 2;
    if (poll(fds, count, kPollMillis) < 0 && errno != EINTR) return Exchange::kDone;
    if (out_open && (fds[0].revents & (POLLIN | POLLHUP | POLLERR))) {
      out_open = out.Drain(pipes.from_stdout);
    }
    if (err_open && (fds[1].revents & (POLLIN | POLLHUP | POLLERR))) {
      err_open = DrainText(pipes.from_stderr, err);
    }
    progress.Update(out.bytes_read(), out.first_count());
    if (count == 3 && (fds[2].revents & (POLLOUT | POLLERR | POLLHUP))) {
      const ssize_t n = write(pipes.to_stdin, bytes.data() + written, bytes.size() - written);
      if (n > 0) written += static_cast<size_t>(n);
      // A child that stops reading (it failed early) closes the pipe: stop feeding it.
      if ((n < 0 && errno != EAGAIN && errno != EINTR) || written == bytes.size()) {
        close(pipes.to_stdin);
        pipes.to_stdin = -1;
      }
    }
  }
  return Exchange::kDone;
}

// What the helper's output is short of, or has too much of, for `what`; OK when it came whole.
absl::Status CheckOutputWhole(const HelperOutputReader& out, absl::string_view what) {
  switch (out.state()) {
    case HelperOutputReader::State::kComplete:
      return absl::OkStatus();
    case HelperOutputReader::State::kTooLarge:
      return absl::InvalidArgumentError(
          absl::StrCat("the Draco decoder returned a ", what, " over its memory limit"));
    case HelperOutputReader::State::kTrailing:
      return absl::InvalidArgumentError(
          absl::StrCat("the Draco decoder returned bytes after its ", what));
    case HelperOutputReader::State::kReading:
      break;
  }
  return absl::InvalidArgumentError(absl::StrCat("the Draco decoder returned a truncated ", what));
}

// Runs the helper on `bytes` with `options` (its arguments after MAX_POINTS), its standard
// output read by `out`; OK when the helper succeeds (`out` may still be short or long).
absl::Status RunHelper(absl::string_view bytes, const DecodeLimits& limits,
                       const std::vector<std::string>& options, const CancelToken& cancel,
                       ProgressRange progress, HelperOutputReader& out) {
  ChildPipes pipes;
  const pid_t pid = StartHelper(limits, options, pipes);
  if (pid < 0) {
    return absl::InternalError(absl::StrCat("cannot start the decoder ", HelperName(limits), ": ",
                                            strerror(errno)));
  }
  std::string err;
  DecodeProgress decode_progress(progress, bytes.size(), pid);
  const Exchange exchange = Communicate(bytes, limits, cancel, pipes, decode_progress, out, err);
  if (exchange != Exchange::kDone) kill(pid, SIGKILL);
  int wait_status = 0;
  while (waitpid(pid, &wait_status, 0) < 0 && errno == EINTR) {
  }
  if (exchange == Exchange::kCancelled) return absl::CancelledError("cancelled while decoding");
  if (exchange == Exchange::kTimedOut) {
    return absl::InvalidArgumentError(absl::StrFormat(
        "%s could not be decoded: the Draco decoder took over %g s", limits.subject,
        limits.timeout_seconds));
  }
  if (WIFSIGNALED(wait_status)) {
    const int sig = WTERMSIG(wait_status);
    // SIGXCPU: over RLIMIT_CPU; SIGABRT/SIGSEGV with RLIMIT_AS: usually a failed allocation.
    return absl::InvalidArgumentError(absl::StrFormat(
        "%s could not be decoded: the Draco decoder died of signal %d (%s)%s", limits.subject,
        sig, strsignal(sig), sig == SIGXCPU ? ", out of CPU time" : ""));
  }
  const int code = WIFEXITED(wait_status) ? WEXITSTATUS(wait_status) : -1;
  if (code == 127) {
    return absl::InternalError(absl::StrCat("cannot run the decoder ", HelperName(limits)));
  }
  if (code == kDecodeHelperOverLimit) {
    return absl::ResourceExhaustedError(absl::StripTrailingAsciiWhitespace(err));
  }
  if (code != 0) {
    return absl::InvalidArgumentError(absl::StrCat(limits.subject, " could not be decoded: ",
                                                   absl::StripTrailingAsciiWhitespace(err)));
  }
  return absl::OkStatus();
}

}  // namespace

absl::StatusOr<PointCloud> DecodeInSubprocess(absl::string_view bytes, const DecodeLimits& limits,
                                              const CancelToken& cancel, ProgressRange progress,
                                              absl::Span<const uint64_t> part_bytes) {
  std::vector<std::string> options;
  if (limits.accept_mesh) options.push_back(kAcceptMeshArgument);
  if (!part_bytes.empty()) {
    options.push_back(absl::StrCat(kPartsArgument, absl::StrJoin(part_bytes, ",")));
    options.push_back(absl::StrCat(kThreadsArgument, std::max(1, limits.threads)));
  }
  PointCloud cloud;
  HelperOutputReader out(static_cast<uint64_t>(limits.memory_bytes));
  out.Add(&cloud.points);
  if (absl::Status s = RunHelper(bytes, limits, options, cancel, progress, out); !s.ok()) return s;
  if (absl::Status s = CheckOutputWhole(out, "point list"); !s.ok()) return s;
  // The child ran Draco on hostile bytes: its points are checked as a file's would be.
  if (absl::Status s = CheckFinitePoints(cloud.points, limits.subject); !s.ok()) return s;
  progress.Done();
  return cloud;
}

absl::StatusOr<TriangleMesh> DecodeMeshInSubprocess(absl::string_view bytes,
                                                    const DecodeLimits& limits,
                                                    const CancelToken& cancel,
                                                    ProgressRange progress) {
  TriangleMesh mesh;
  HelperOutputReader out(static_cast<uint64_t>(limits.memory_bytes));
  out.Add(&mesh.vertices);
  out.Add(&mesh.faces);
  if (absl::Status s = RunHelper(bytes, limits, {kMeshArgument}, cancel, progress, out); !s.ok()) {
    return s;
  }
  if (absl::Status s = CheckOutputWhole(out, "mesh"); !s.ok()) return s;
  absl::Status s = CheckFinitePoints(mesh.vertices, limits.subject, /*is_mesh=*/true);
  if (s.ok()) s = CheckFaceIndices(mesh, limits.subject);
  if (!s.ok()) return s;
  progress.Done();
  return mesh;
}

}  // namespace membrane
