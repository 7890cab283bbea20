// Runs one measurement in a forked child, so that each point count of a bench starts from a
// fresh heap and its own peak RSS (the high-water mark never goes down within a process).
#ifndef MEMBRANE_TESTS_BENCH_CHILD_PROCESS_H_
#define MEMBRANE_TESTS_BENCH_CHILD_PROCESS_H_

#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <type_traits>

#include "absl/functional/function_ref.h"

namespace membrane::bench {

// Forks, calls `run` in the child and returns its Row through a pipe. Row must be trivially
// copyable (it crosses the pipe as bytes). A Row{} comes back when the fork or pipe fails, the
// child dies or writes a short row, so a default Row must read as "not measured".
template <typename Row>
Row RunInChild(absl::FunctionRef<Row()> run) {
  static_assert(std::is_trivially_copyable_v<Row>, "a Row crosses the pipe as bytes");
  int fds[2];
  if (pipe(fds) != 0) return Row{};
  std::fflush(stdout);
  const pid_t pid = fork();
  if (pid < 0) return Row{};
  if (pid == 0) {
    close(fds[0]);
    const Row row = run();
    const ssize_t n = write(fds[1], &row, sizeof row);
    _exit(n == static_cast<ssize_t>(sizeof row) ? 0 : 1);
  }
  close(fds[1]);
  Row row;
  const ssize_t n = read(fds[0], &row, sizeof row);
  close(fds[0]);
  int status = 0;
  waitpid(pid, &status, 0);
  if (n != static_cast<ssize_t>(sizeof row) || !WIFEXITED(status) || WEXITSTATUS(status) != 0)
    return Row{};
  return row;
}

}  // namespace membrane::bench

#endif  // MEMBRANE_TESTS_BENCH_CHILD_PROCESS_H_
