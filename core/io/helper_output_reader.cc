#include "core/io/helper_output_reader.h"

#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace membrane {

HelperOutputReader::HelperOutputReader(uint64_t max_section_bytes)
    : max_section_bytes_(max_section_bytes) {}

char* HelperOutputReader::Destination(size_t& wanted) {
  if (too_large_ || trailing_ || section_ == sections_.size()) return nullptr;
  if (in_count_) {
    wanted = sizeof(uint64_t) - count_have_;
    return reinterpret_cast<char*>(count_bytes_) + count_have_;
  }
  wanted = static_cast<size_t>(records_total_ - records_have_);
  return records_ + records_have_;
}

void HelperOutputReader::Advance(size_t n) {
  bytes_read_ += n;
  if (!in_count_) {
    records_have_ += n;
  } else {
    count_have_ += n;
    if (count_have_ < sizeof(uint64_t)) return;
    uint64_t count = 0;
    std::memcpy(&count, count_bytes_, sizeof count);
    if (section_ == 0) first_count_ = count;
    const Section& section = sections_[section_];
    if (count > max_section_bytes_ / section.record_bytes) {
      too_large_ = true;
      return;
    }
    records_total_ = count * section.record_bytes;
    records_have_ = 0;
    records_ = section.size_to(count);
    in_count_ = false;
    count_have_ = 0;
  }
  if (records_have_ == records_total_) {  // an empty section is whole at once
    ++section_;
    in_count_ = true;
    records_ = nullptr;
  }
}

bool HelperOutputReader::Drain(int fd) {
  char scratch[1 << 12];
  while (true) {
    size_t wanted = 0;
    char* to = Destination(wanted);
    const bool dropping = to == nullptr;
    if (dropping) {
      to = scratch;
      wanted = sizeof scratch;
    }
    const ssize_t n = read(fd, to, wanted);
    if (n > 0) {
      if (!dropping) {
        Advance(static_cast<size_t>(n));
      } else {
        bytes_read_ += static_cast<uint64_t>(n);
        if (!too_large_) trailing_ = true;
      }
      continue;
    }
    if (n < 0 && (errno == EAGAIN || errno == EINTR)) return true;
    return false;
  }
}

HelperOutputReader::State HelperOutputReader::state() const {
  if (too_large_) return State::kTooLarge;
  if (trailing_) return State::kTrailing;
  return section_ == sections_.size() ? State::kComplete : State::kReading;
}

}  // namespace membrane
