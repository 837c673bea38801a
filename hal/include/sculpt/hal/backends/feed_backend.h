#pragma once
// A backend whose devices are fed by the program: the byte-level fake
// transport of the tests, and the base a replay backend can use (the sim
// module feeds recorded RawEvents with their recorded t_ns). Devices are
// attached and detached at will, so plugging, unplugging and re-plugging are
// reproducible.
//
// Thread safety: attach/detach/push/remove from any thread; the Device is
// read by its reader thread.

#include <condition_variable>
#include <deque>
#include <map>
#include <memory>
#include <mutex>
#include <string>

#include "sculpt/hal/types/device.h"

namespace sculpt::hal {

/// The feeding end of one attached device (shared with its open Device).
class DeviceFeed {
 public:
  explicit DeviceFeed(DeviceInfo info) : info_(std::move(info)) {}
  const DeviceInfo& info() const { return info_; }
  /// Queues one event for the reader.
  void push(const RawEvent& event);
  /// The device vanishes: the reader gets kRemoved after what is queued.
  void remove(int64_t t_ns);
  /// Waits until the reader took every queued event (or timeout_ms passed).
  bool wait_drained(int timeout_ms);
  /// Reader side.
  ReadResult read(RawEvent& out, int timeout_ms);
  bool removed() const;

 private:
  DeviceInfo info_;
  mutable std::mutex mutex_;
  std::condition_variable cv_;
  std::deque<RawEvent> queue_;
  bool removed_ = false;
  int64_t removed_t_ns_ = 0;
};

class FeedBackend final : public Backend {
 public:
  explicit FeedBackend(std::string name = "sim") : name_(std::move(name)) {}
  std::string_view name() const override { return name_; }
  BackendStatus status() override { return {}; }
  Result<std::vector<DeviceInfo>> enumerate() override;
  Result<std::unique_ptr<Device>> open(const DeviceInfo& info) override;
  bool changed() override;

  /// Plugs a device in (info.backend is set to this backend's name). Returns
  /// its feed. Attaching a path again replaces it (a re-plug).
  std::shared_ptr<DeviceFeed> attach(DeviceInfo info);
  /// Unplugs: the open Device, if any, reads kRemoved; enumerate() no longer lists it.
  void detach(const std::string& path, int64_t t_ns);

 private:
  std::string name_;
  std::mutex mutex_;
  std::map<std::string, std::shared_ptr<DeviceFeed>> feeds_;
  bool changed_ = true;
};

}  // namespace sculpt::hal
