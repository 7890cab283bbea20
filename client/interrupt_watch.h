// What Ctrl-C does to `membrane reconstruct --server`: the job lives on the server, so
// stopping the client must say what becomes of it: a silent exit leaves the user unable to tell
// whether the job runs on, or how to get its mesh.
#ifndef MEMBRANE_CLIENT_INTERRUPT_WATCH_H_
#define MEMBRANE_CLIENT_INTERRUPT_WATCH_H_

#include <signal.h>

#include <string>
#include <thread>

#include "absl/base/thread_annotations.h"
#include "absl/synchronization/mutex.h"
#include "client/server_connection.h"

namespace membrane::client {

// On SIGINT or SIGTERM: when no job has been accepted yet, prints "membrane: interrupted
// before the server accepted the job; nothing runs there"; when one has, either cancels it
// (cancel_job) and says so, or prints how to follow it ("membrane jobs watch ID ..."). Then
// exits the process with 130 (128 + SIGINT), as shells expect of an interrupted command.
//
// Construct it on the main thread BEFORE any other thread starts (gRPC's included): it
// blocks the two signals in the calling thread, so that every thread created later inherits
// the mask and only this watch's own thread receives them. The destructor stops that thread
// and restores the mask. One instance per process at a time.
class InterruptWatch {
 public:
  // `server` names where the job runs (for the printed command and for the cancel); `output`
  // the -o path to repeat in it ("" for none).
  InterruptWatch(ServerConnection server, std::string output, bool cancel_job);
  ~InterruptWatch();

  InterruptWatch(const InterruptWatch&) = delete;
  InterruptWatch& operator=(const InterruptWatch&) = delete;

  // The id the server gave the job; called from the thread following the job.
  void JobAccepted(const std::string& job_id);

 private:
  void Run();
  // Prints what becomes of the job (cancelling it first when asked), then exits.
  [[noreturn]] void OnInterrupt();

  const ServerConnection server_;
  const std::string output_;
  const bool cancel_job_;
  sigset_t previous_mask_;
  int signal_fd_ = -1;
  int stop_fd_ = -1;  // an eventfd the destructor writes to end Run
  absl::Mutex mu_;
  std::string job_id_ ABSL_GUARDED_BY(mu_);
  std::thread thread_;
};

}  // namespace membrane::client

#endif  // MEMBRANE_CLIENT_INTERRUPT_WATCH_H_
