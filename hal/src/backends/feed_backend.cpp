#include "sculpt/hal/backends/feed_backend.h"

#include <chrono>

namespace sculpt::hal {

void DeviceFeed::push(const RawEvent& event) {
  {
    std::lock_guard lock(mutex_);
    if (removed_) return;  // a vanished device sends nothing more
    queue_.push_back(event);
  }
  cv_.notify_all();
}

void DeviceFeed::remove(int64_t t_ns) {
  {
    std::lock_guard lock(mutex_);
    removed_ = true;
    removed_t_ns_ = t_ns;
  }
  cv_.notify_all();
}

bool DeviceFeed::removed() const {
  std::lock_guard lock(mutex_);
  return removed_;
}

bool DeviceFeed::wait_drained(int timeout_ms) {
  std::unique_lock lock(mutex_);
  return cv_.wait_for(lock, std::chrono::milliseconds(timeout_ms), [&] { return queue_.empty(); });
}

ReadResult DeviceFeed::read(RawEvent& out, int timeout_ms) {
  std::unique_lock lock(mutex_);
  cv_.wait_for(lock, std::chrono::milliseconds(timeout_ms),
               [&] { return !queue_.empty() || removed_; });
  if (!queue_.empty()) {
    out = queue_.front();
    queue_.pop_front();
    if (queue_.empty()) cv_.notify_all();  // wakes wait_drained
    return ReadResult::kEvent;
  }
  if (removed_) {
    out = RawEvent::removed(removed_t_ns_);
    return ReadResult::kRemoved;
  }
  return ReadResult::kTimeout;
}

namespace {

class FeedDevice final : public Device {
 public:
  explicit FeedDevice(std::shared_ptr<DeviceFeed> feed) : feed_(std::move(feed)) {}
  const DeviceInfo& info() const override { return feed_->info(); }
  ReadResult read(RawEvent& out, int timeout_ms) override { return feed_->read(out, timeout_ms); }

 private:
  std::shared_ptr<DeviceFeed> feed_;
};

}  // namespace

Result<std::vector<DeviceInfo>> FeedBackend::enumerate() {
  std::lock_guard lock(mutex_);
  std::vector<DeviceInfo> out;
  for (const auto& [path, feed] : feeds_)
    out.push_back(feed->info());
  return out;
}

Result<std::unique_ptr<Device>> FeedBackend::open(const DeviceInfo& info) {
  std::lock_guard lock(mutex_);
  const auto it = feeds_.find(info.path);
  if (it == feeds_.end()) return Error(info.id() + ": no such device (unplugged?)");
  return std::unique_ptr<Device>(std::make_unique<FeedDevice>(it->second));
}

bool FeedBackend::changed() {
  std::lock_guard lock(mutex_);
  const bool c = changed_;
  changed_ = false;
  return c;
}

std::shared_ptr<DeviceFeed> FeedBackend::attach(DeviceInfo info) {
  info.backend = name_;
  auto feed = std::make_shared<DeviceFeed>(info);
  std::lock_guard lock(mutex_);
  if (auto it = feeds_.find(info.path); it != feeds_.end()) it->second->remove(0);
  feeds_[info.path] = feed;
  changed_ = true;
  return feed;
}

void FeedBackend::detach(const std::string& path, int64_t t_ns) {
  std::lock_guard lock(mutex_);
  if (auto it = feeds_.find(path); it != feeds_.end()) {
    it->second->remove(t_ns);
    feeds_.erase(it);
    changed_ = true;
  }
}

}  // namespace sculpt::hal
