#include "server/idle_watchdog.h"

#include <algorithm>
#include <utility>

namespace membrane::server {

IdleWatchdog::IdleWatchdog(absl::Duration idle_limit, const Clock& clock,
                           std::function<void()> on_cut)
    : limit_(idle_limit), clock_(clock), on_cut_(std::move(on_cut)) {
  if (limit_ > absl::ZeroDuration()) thread_ = std::thread([this] { Loop(); });
}

IdleWatchdog::~IdleWatchdog() {
  {
    absl::MutexLock lock(&mutex_);
    stopping_ = true;
  }
  if (thread_.joinable()) thread_.join();
}

IdleWatchdog::Watch IdleWatchdog::Start(grpc::ServerContext* context) {
  return Start([context] { context->TryCancel(); });
}

IdleWatchdog::Watch IdleWatchdog::Start(std::function<void()> cancel) {
  if (limit_ <= absl::ZeroDuration()) return Watch(nullptr, 0);
  absl::MutexLock lock(&mutex_);
  const int64_t id = next_id_++;
  calls_[id] = Entry{std::move(cancel), clock_.Now()};
  return Watch(this, id);
}

IdleWatchdog::Watch::~Watch() {
  if (owner_ == nullptr) return;
  absl::MutexLock lock(&owner_->mutex_);
  owner_->calls_.erase(id_);
}

void IdleWatchdog::Watch::Touch() {
  if (owner_ == nullptr) return;
  absl::MutexLock lock(&owner_->mutex_);
  owner_->calls_[id_].last = owner_->clock_.Now();
}

bool IdleWatchdog::Watch::fired() const {
  if (owner_ == nullptr) return false;
  absl::MutexLock lock(&owner_->mutex_);
  auto it = owner_->calls_.find(id_);
  return it != owner_->calls_.end() && it->second.fired;
}

void IdleWatchdog::Loop() {
  // A quarter of the limit between looks (at most a second): a call is ended within 1.25
  // limits of its last progress.
  const absl::Duration period = std::min(limit_ / 4, absl::Seconds(1));
  absl::MutexLock lock(&mutex_);
  while (!stopping_) {
    mutex_.AwaitWithTimeout(absl::Condition(&stopping_), period);
    const absl::Time now = clock_.Now();
    for (auto& [id, entry] : calls_) {
      if (entry.fired || now - entry.last <= limit_) continue;
      // Counted first: whoever sees the call end sees it counted.
      if (on_cut_) on_cut_();
      // Under the lock: the Watch, and so what `cancel` reaches, cannot go away meanwhile.
      entry.cancel();
      entry.fired = true;
    }
  }
}

}  // namespace membrane::server
