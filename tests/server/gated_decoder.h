// A decoder for membraned's decoder path (--decoder_path, ServerOptions::decoder_path) that
// holds each decode until the test lets it go. A job is then running, in its decode stage, for
// as long as the test wants, whatever the machine's load: tests of cancels, deadlines, full
// queues and restarts wait on events, never on a job being slow. A held decode ends like any
// other when its job is cancelled or its server stops (the decoder process is killed).
#ifndef MEMBRANE_TESTS_SERVER_GATED_DECODER_H_
#define MEMBRANE_TESTS_SERVER_GATED_DECODER_H_

#include <string>

#include "tests/support/scratch_dir.h"

namespace membrane::testing {

class GatedDecoder {
 public:
  // Writes the decoder, a shell script, and its gate, a FIFO, into `dir` (which must outlive
  // this object). Each run of the script opens the gate read-write (so that the open does not
  // wait for a writer), appends a line to a file of its own, waits for a line from the gate,
  // then runs `decoder` (a membrane-decode binary) with its arguments and input. Fails the
  // test when the files cannot be made. The object holds the gate open for reading and
  // writing itself, so that lines written wait in the FIFO for the decodes to come.
  GatedDecoder(const ScratchDir& dir, const std::string& decoder);
  // Lets every decode still at the gate go on (one of a server killed outright would wait
  // there for ever), then closes the gate.
  ~GatedDecoder();
  GatedDecoder(const GatedDecoder&) = delete;
  GatedDecoder& operator=(const GatedDecoder&) = delete;

  // The script, for the server's decoder path.
  const std::string& path() const { return script_; }

  // How many decodes have reached the gate so far (those let through included).
  int Decodes() const;
  // Waits until `count` decodes in all have reached the gate: true, or false after `seconds`.
  bool WaitForDecodes(int count, double seconds = 60) const;

  // Lets one decode go on: the first held at the gate, or else the next to reach it.
  void Open() const;

 private:
  std::string script_;
  std::string gate_;
  std::string arrivals_;  // one line per decode that reached the gate
  int gate_fd_ = -1;      // the gate, read-write
};

}  // namespace membrane::testing

#endif  // MEMBRANE_TESTS_SERVER_GATED_DECODER_H_
