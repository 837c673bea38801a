#pragma once
// The registry owns the backends and the open devices. scan() enumerates
// every backend, picks the best backend per physical device (the first in
// priority order that sees it: spnav when spacenavd owns the device, then
// hidapi, then evdev, then libusb, which has to detach the kernel driver) and opens it
// once; a device already open through any backend is never opened again.
// Readers whose device vanished are retired by poll(), so the next scan()
// picks up a re-plug.

#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "sculpt/hal/input/device_reader.h"
#include "sculpt/hal/normalizer/normalizer_config.h"
#include "sculpt/hal/types/device.h"

namespace sculpt::hal {

/// What one backend sees, for `sculpt devices`.
struct BackendListing {
  std::string backend;
  BackendStatus status;
  std::vector<DeviceInfo> devices;
  std::string error;  ///< enumeration failed: why
};

struct ScanReport {
  std::vector<uint32_t> opened;     ///< device ids of readers started by this scan
  std::vector<std::string> errors;  ///< one line per device that could not be opened
};

class DeviceRegistry {
 public:
  /// backends in priority order (best first). Its readers ring
  /// options.doorbell, or a doorbell of its own when that is null.
  explicit DeviceRegistry(std::vector<std::unique_ptr<Backend>> backends,
                          NormalizerConfig config = {}, ReaderOptions options = {});
  ~DeviceRegistry();

  /// The hardware backends in their default priority: spnav, hidapi, evdev, libusb.
  static std::vector<std::unique_ptr<Backend>> default_backends();

  /// Adds a backend (the sim replay backend, say) at the end of the priority
  /// order, or at the front.
  void add_backend(std::unique_ptr<Backend> backend, bool first = false);

  /// Opens one device chosen by the user (`--device ID`): "backend:path" as
  /// `sculpt devices` prints it, "backend" for that backend's first device,
  /// or "vvvv:pppp" for the first device with that vendor:product. Errors
  /// name the id and what was looked for. A device already open is not
  /// opened twice: its id is returned.
  Result<uint32_t> open_device(const std::string& id);

  /// Lists every backend's view (no device is opened).
  std::vector<BackendListing> list();

  /// Opens the devices not yet open (only backends whose changed() is true
  /// are enumerated again).
  ScanReport scan();

  /// Drains every reader into `frame` and retires finished ones.
  void poll(InputFrame& frame, int64_t now_ns);

  /// Rung by every reader once it has pushed a report's events: the
  /// poller sleeps on it between polls (InputHub::run()).
  const Doorbell& doorbell() const { return *options_.doorbell; }

  size_t open_count() const { return readers_.size(); }
  const DeviceReader* reader(uint32_t device_id) const;
  /// The open device with the lowest id (the one open longest), if any. Ids
  /// are never reused: a device plugged in again gets the next one.
  std::optional<uint32_t> first_device() const;

 private:
  Result<uint32_t> start_reader(Backend& backend, const DeviceInfo& info);

  std::vector<std::unique_ptr<Backend>> backends_;
  NormalizerConfig config_;
  ReaderOptions options_;
  std::map<uint32_t, std::unique_ptr<DeviceReader>> readers_;
  std::map<std::string, uint32_t> open_keys_;                 // physical key -> device id
  std::map<std::string, std::vector<DeviceInfo>> last_seen_;  // backend -> last enumeration
  uint32_t next_id_ = 1;
};

}  // namespace sculpt::hal
