// The decode helper's standard output (decode_helper.h: sections of a little-endian uint64
// count followed by that many fixed-size records) read as it arrives, each section's records
// straight into the vector that keeps them. A 10M-point cloud is 120 MB: gathering it in a
// growing string and then copying it into its vector would write it three times over in fresh
// pages, on one thread after the child has finished (1.2 s of a 2.5 s decode stage).
#ifndef MEMBRANE_CORE_IO_HELPER_OUTPUT_READER_H_
#define MEMBRANE_CORE_IO_HELPER_OUTPUT_READER_H_

#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

namespace membrane {

class HelperOutputReader {
 public:
  // How the output has gone so far.
  enum class State {
    kReading,   // a section has not come whole yet
    kComplete,  // every section has come whole, and nothing after them
    kTooLarge,  // a count asks for more than max_section_bytes
    kTrailing,  // bytes came after the last section
  };

  // `max_section_bytes`: a count whose records would take more bytes is refused before its
  // vector is sized (the helper's own memory limit: a helper within it cannot have held more).
  explicit HelperOutputReader(uint64_t max_section_bytes);

  // Adds a section read into `items` (resized to its count, then filled), after the sections
  // added before. T must be trivially copyable; the bytes are the host's layout (the helper is
  // this build's). `items` must outlive the reading.
  template <typename T>
  void Add(std::vector<T>* items) {
    sections_.push_back({sizeof(T), [items](uint64_t count) {
                           items->resize(count);
                           return reinterpret_cast<char*>(items->data());
                         }});
  }

  // Reads what the non-blocking `fd` has, into the sections in order; once the reader is no
  // longer kReading, what comes is read and dropped (so that the writer is never left
  // blocked). Returns false at end of file or on a read error other than EAGAIN/EINTR.
  bool Drain(int fd);

  State state() const;
  uint64_t bytes_read() const { return bytes_read_; }
  // The first section's count, once its 8 bytes have come (the decode's progress).
  std::optional<uint64_t> first_count() const { return first_count_; }

 private:
  struct Section {
    size_t record_bytes;
    std::function<char*(uint64_t count)> size_to;  // sizes the vector, returns its bytes
  };

  // Where the next bytes go and how many the current piece still needs; nullptr once every
  // section is whole or the reader has failed.
  char* Destination(size_t& wanted);
  // Counts `n` bytes read into Destination's place.
  void Advance(size_t n);

  const uint64_t max_section_bytes_;
  std::vector<Section> sections_;
  size_t section_ = 0;         // the section being read
  bool in_count_ = true;       // reading its count (else its records)
  unsigned char count_bytes_[sizeof(uint64_t)] = {};
  size_t count_have_ = 0;      // bytes of the count read
  char* records_ = nullptr;    // the section's vector's bytes, once sized
  uint64_t records_total_ = 0;  // bytes of the section's records
  uint64_t records_have_ = 0;  // of them read
  uint64_t bytes_read_ = 0;
  std::optional<uint64_t> first_count_;
  bool too_large_ = false;
  bool trailing_ = false;
};

}  // namespace membrane

#endif  // MEMBRANE_CORE_IO_HELPER_OUTPUT_READER_H_
