#include "server/event_log.h"

#include <cstdint>
#include <cstring>

namespace membrane::server {

void EventLog::Append(const v1::JobEvent& event) {
  const size_t size = event.ByteSizeLong();
  char* at = records_.Extend(sizeof(uint32_t) + size);
  const uint32_t length = static_cast<uint32_t>(size);  // an event is at most a few KiB
  std::memcpy(at, &length, sizeof length);
  event.SerializeWithCachedSizesToArray(reinterpret_cast<uint8_t*>(at + sizeof(uint32_t)));
  ++count_;
}

void EventLog::CopyFrom(size_t first, std::vector<v1::JobEvent>& out) const {
  const absl::string_view all = records_.view();
  size_t at = 0;
  for (size_t i = 0; i < count_; ++i) {
    uint32_t size;
    std::memcpy(&size, all.data() + at, sizeof size);
    at += sizeof(uint32_t);
    // Each record was serialized here from a message of this build, so it parses.
    if (i >= first) out.emplace_back().ParseFromArray(all.data() + at, static_cast<int>(size));
    at += size;
  }
}

}  // namespace membrane::server
