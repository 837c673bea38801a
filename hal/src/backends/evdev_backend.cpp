// evdev backend: the 6-axis event nodes as a Backend (see
// sculpt/hal/backends/evdev_backend.h for what it implements and lacks).

#include "sculpt/hal/backends/evdev_backend.h"

#include <algorithm>
#include <utility>

#include "backends/evdev_ff/linux_evdev_io.h"
#include "backends/evdev_input/evdev_input_backend.h"

namespace sculpt::hal {
namespace evdev_input {
namespace {

class EvdevInputBackend final : public Backend {
 public:
  EvdevInputBackend(EvdevIoFactory factory, EvdevInputOptions options)
      : factory_(std::move(factory)), options_(std::move(options)), lister_(factory_()) {}

  std::string_view name() const override { return "evdev"; }
  // The kernel interface needs no library or daemon.
  BackendStatus status() override { return {}; }

  Result<std::vector<DeviceInfo>> enumerate() override {
    listed_nodes_ = lister_->list_event_nodes();
    std::vector<DeviceInfo> found = list_evdev_6axis_devices(*lister_, options_);
    // udev sets a new node's permissions just after creating it: keep
    // asking while one is not ours yet.
    retry_ =
        std::any_of(found.begin(), found.end(), [](const DeviceInfo& d) { return !d.accessible; });
    return found;
  }

  Result<std::unique_ptr<Device>> open(const DeviceInfo& info) override {
    auto device = EvdevInputDevice::open(factory_(), info.path, options_);
    if (!device) return device.error();
    return std::unique_ptr<Device>(std::move(device).value());
  }

  // Hot-plug: a node came or went (reading the directory is cheap; no
  // inotify or udev monitor needed at the registry's scan rate).
  bool changed() override { return retry_ || lister_->list_event_nodes() != listed_nodes_; }

 private:
  EvdevIoFactory factory_;
  EvdevInputOptions options_;
  std::unique_ptr<evdev_ff::EvdevIo> lister_;
  std::vector<std::string> listed_nodes_;
  bool retry_ = true;
};

}  // namespace

std::unique_ptr<Backend> make_evdev_input_backend(EvdevIoFactory factory,
                                                  EvdevInputOptions options) {
  return std::make_unique<EvdevInputBackend>(std::move(factory), std::move(options));
}

}  // namespace evdev_input

std::unique_ptr<Backend> make_evdev_backend() {
  return evdev_input::make_evdev_input_backend(
      [] { return std::make_unique<evdev_ff::LinuxEvdevIo>(); });
}

}  // namespace sculpt::hal
