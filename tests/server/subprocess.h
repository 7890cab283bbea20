// A child process for end-to-end tests: membraned, or a `membrane` client that must run
// while the test does something else.
#ifndef MEMBRANE_TESTS_SERVER_SUBPROCESS_H_
#define MEMBRANE_TESTS_SERVER_SUBPROCESS_H_

#include <sys/types.h>

#include <string>
#include <vector>

namespace membrane::testing {

class Subprocess {
 public:
  // Starts `argv` (argv[0] a path; no shell) with stdin from /dev/null and stdout and stderr
  // to the files `out_path` and `err_path`.
  Subprocess(const std::vector<std::string>& argv, const std::string& out_path,
             const std::string& err_path);
  // Kills the process (SIGKILL) unless it has been waited for.
  ~Subprocess();

  Subprocess(const Subprocess&) = delete;
  Subprocess& operator=(const Subprocess&) = delete;

  // Sends `signal_number`.
  void Signal(int signal_number);
  // Waits up to `seconds` for the exit; the exit status (128 + signal when killed), or -1 on
  // timeout (the process is then killed).
  int Wait(double seconds);
  // Its process id (for /proc); -1 when it could not be started.
  pid_t pid() const { return pid_; }

 private:
  pid_t pid_ = -1;
  bool reaped_ = false;
};

// Waits up to `seconds` for `path` to contain `text`; returns the file's content then (or at
// the timeout).
std::string WaitForText(const std::string& path, const std::string& text, double seconds);

// The whole of `path`, or "" when it cannot be read.
std::string ReadText(const std::string& path);

}  // namespace membrane::testing

#endif  // MEMBRANE_TESTS_SERVER_SUBPROCESS_H_
