// A job's events, kept serialized in pages of their own (MappedBytes) rather than as messages
// whose blocks a run's late stages would cut from the arrays they freed.
#ifndef MEMBRANE_SERVER_EVENT_LOG_H_
#define MEMBRANE_SERVER_EVENT_LOG_H_

#include <cstddef>
#include <vector>

#include "membrane/v1/reconstruction.pb.h"
#include "server/mapped_bytes.h"

namespace membrane::server {

// Not thread-safe: its owner (the Job) locks.
class EventLog {
 public:
  // Appends `event`, serialized straight into the log (no block of the heap kept for it).
  void Append(const v1::JobEvent& event);

  // Appends the events from the `first`-th on to `out`, in order (none if first >= size()).
  void CopyFrom(size_t first, std::vector<v1::JobEvent>& out) const;

  size_t size() const { return count_; }
  // Bytes the events take serialized, with their lengths.
  size_t bytes() const { return records_.size(); }

 private:
  MappedBytes records_;  // each event as a fixed32 length, then its bytes
  size_t count_ = 0;
};

}  // namespace membrane::server

#endif  // MEMBRANE_SERVER_EVENT_LOG_H_
