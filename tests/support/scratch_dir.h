// A fresh temporary directory per test, removed with everything in it at the end.
#ifndef MEMBRANE_TESTS_SUPPORT_SCRATCH_DIR_H_
#define MEMBRANE_TESTS_SUPPORT_SCRATCH_DIR_H_

#include <string>

namespace membrane::testing {

class ScratchDir {
 public:
  // Creates a new directory under $TMPDIR (or /tmp). Aborts the test binary if it cannot:
  // no test of the command line means anything without one.
  ScratchDir();
  ~ScratchDir();
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;

  const std::string& path() const { return path_; }
  // path() + "/" + name.
  std::string File(const std::string& name) const { return path_ + "/" + name; }

 private:
  std::string path_;
};

}  // namespace membrane::testing

#endif  // MEMBRANE_TESTS_SUPPORT_SCRATCH_DIR_H_
