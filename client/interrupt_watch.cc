#include "client/interrupt_watch.h"

#include <poll.h>
#include <pthread.h>
#include <sys/eventfd.h>
#include <sys/signalfd.h>
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <utility>

#include <grpcpp/client_context.h>

#include "absl/strings/str_cat.h"
#include "absl/time/clock.h"
#include "absl/time/time.h"
#include "membrane/v1/reconstruction.grpc.pb.h"

namespace membrane::client {
namespace {

constexpr int kInterruptedExit = 128 + SIGINT;

sigset_t StopSignals() {
  sigset_t set;
  sigemptyset(&set);
  sigaddset(&set, SIGINT);
  sigaddset(&set, SIGTERM);
  return set;
}

// The shell words of `text`, quoted when they need it.
std::string ShellWord(const std::string& text) {
  if (!text.empty() && text.find_first_of(" \t\n'\"\\$`*?[]{}()<>|&;!#~") == std::string::npos) {
    return text;
  }
  std::string quoted = "'";
  for (char c : text) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

}  // namespace

InterruptWatch::InterruptWatch(ServerConnection server, std::string output, bool cancel_job)
    : server_(std::move(server)), output_(std::move(output)), cancel_job_(cancel_job) {
  const sigset_t stop = StopSignals();
  pthread_sigmask(SIG_BLOCK, &stop, &previous_mask_);
  signal_fd_ = signalfd(-1, &stop, SFD_CLOEXEC);
  stop_fd_ = eventfd(0, EFD_CLOEXEC);
  // Without the descriptors Ctrl-C keeps its default effect; the signals are unblocked again.
  if (signal_fd_ < 0 || stop_fd_ < 0) {
    pthread_sigmask(SIG_SETMASK, &previous_mask_, nullptr);
    return;
  }
  thread_ = std::thread([this] { Run(); });
}

InterruptWatch::~InterruptWatch() {
  if (thread_.joinable()) {
    const uint64_t one = 1;
    if (write(stop_fd_, &one, sizeof one) == sizeof one) thread_.join();
    else thread_.detach();
  }
  if (signal_fd_ >= 0) close(signal_fd_);
  if (stop_fd_ >= 0) close(stop_fd_);
  pthread_sigmask(SIG_SETMASK, &previous_mask_, nullptr);
}

void InterruptWatch::JobAccepted(const std::string& job_id) {
  absl::MutexLock lock(&mu_);
  job_id_ = job_id;
}

void InterruptWatch::Run() {
  pollfd fds[2] = {{signal_fd_, POLLIN, 0}, {stop_fd_, POLLIN, 0}};
  while (true) {
    if (poll(fds, 2, -1) < 0) continue;  // EINTR
    if (fds[1].revents != 0) return;
    if (fds[0].revents != 0) OnInterrupt();
  }
}

void InterruptWatch::OnInterrupt() {
  std::string job_id;
  {
    absl::MutexLock lock(&mu_);
    job_id = job_id_;
  }
  // The progress line in flight ends first, so that the message starts a line of its own.
  std::fputs("\n", stderr);
  if (job_id.empty()) {
    std::fputs("membrane: interrupted before the server accepted the job; nothing runs there\n",
               stderr);
    std::fflush(stderr);
    std::_Exit(kInterruptedExit);
  }
  if (cancel_job_) {
    const grpc::Status status = CancelRemoteJob(server_, job_id, absl::Seconds(5));
    if (status.ok()) {
      std::fprintf(stderr, "membrane: interrupted; job %s cancelled on %s\n", job_id.c_str(),
                   server_.address.c_str());
    } else {
      std::fprintf(stderr,
                   "membrane: interrupted; job %s could not be cancelled (%s): it goes on; "
                   "`membrane jobs cancel %s --server %s` stops it\n",
                   job_id.c_str(), status.error_message().c_str(), job_id.c_str(),
                   ShellWord(server_.address).c_str());
    }
  } else {
    std::fprintf(stderr,
                 "membrane: interrupted; job %s goes on on %s; get its mesh with: membrane "
                 "jobs watch %s --server %s%s%s\n",
                 job_id.c_str(), server_.address.c_str(), job_id.c_str(),
                 ShellWord(server_.address).c_str(),
                 output_.empty() ? "" : absl::StrCat(" -o ", ShellWord(output_)).c_str(),
                 server_.token.empty() && server_.tls_ca_pem.empty()
                     ? ""
                     : " (and your --token-file / --tls-ca)");
  }
  std::fflush(stderr);
  std::_Exit(kInterruptedExit);
}

}  // namespace membrane::client
