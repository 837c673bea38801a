// hidapi backend (hidraw flavour).
// Implements: enumeration of known 3Dconnexion devices and of any multi-axis
// controller, permission check on the node, report descriptor and USB
// location from sysfs, blocking reads with timeout, removal on read error.
// Lacks: hotplug notification (hidapi has none; the registry polls), output
// reports (LEDs).

#include "sculpt/hal/backends/hidapi_backend.h"

#include "backends/not_built_backend.h"

#if SCULPT_HAL_HAVE_HIDAPI
#include <hidapi/hidapi.h>
#include <unistd.h>

#include <cwchar>

#include "backends/sysfs_hidraw.h"
#include "sculpt/hal/types/clock.h"
#include "sculpt/hal/types/quirks.h"
#endif

namespace sculpt::hal {
namespace {

#if SCULPT_HAL_HAVE_HIDAPI

std::string narrow(const wchar_t* w) {
  if (w == nullptr) return {};
  std::string out;
  for (; *w; ++w)
    out.push_back(*w < 128 ? static_cast<char>(*w) : '?');
  return out;
}

class HidapiDevice final : public Device {
 public:
  HidapiDevice(hid_device* handle, DeviceInfo info) : handle_(handle), info_(std::move(info)) {}
  ~HidapiDevice() override { hid_close(handle_); }
  const DeviceInfo& info() const override { return info_; }

  ReadResult read(RawEvent& out, int timeout_ms) override {
    if (gone_) {
      out = RawEvent::removed(monotonic_ns());
      return ReadResult::kRemoved;
    }
    // One more byte than we keep, so that an over-long report is noticed.
    uint8_t buf[RawEvent::kMaxReportBytes + 1];
    const int n = hid_read_timeout(handle_, buf, sizeof buf, timeout_ms);
    const int64_t t = monotonic_ns();
    if (n < 0) {  // hidraw returns an error once the device is unplugged
      gone_ = true;
      out = RawEvent::removed(t);
      return ReadResult::kRemoved;
    }
    if (n == 0) return ReadResult::kTimeout;
    out = RawEvent::report(t, std::span<const uint8_t>(buf, static_cast<size_t>(n)));
    return ReadResult::kEvent;
  }

 private:
  hid_device* handle_;
  DeviceInfo info_;
  bool gone_ = false;
};

class HidapiBackend final : public Backend {
 public:
  HidapiBackend() { init_ok_ = hid_init() == 0; }
  ~HidapiBackend() override {
    if (init_ok_) hid_exit();
  }
  std::string_view name() const override { return "hidapi"; }
  BackendStatus status() override {
    if (!init_ok_) return {BackendState::kUnavailable, "hid_init failed"};
    return {};
  }

  Result<std::vector<DeviceInfo>> enumerate() override {
    if (!init_ok_) return Error("hidapi: hid_init failed");
    std::vector<DeviceInfo> out;
    hid_device_info* list = hid_enumerate(0, 0);
    for (hid_device_info* d = list; d != nullptr; d = d->next) {
      const DeviceQuirks* q = find_quirks(d->vendor_id, d->product_id);
      const bool multi_axis = d->usage_page == 1 && d->usage == 8;
      if (q == nullptr && !multi_axis) continue;  // keyboards, mice, ...
      if (is_ignored(d->vendor_id, d->product_id, d->usage_page, d->usage)) continue;
      DeviceInfo info;
      info.backend = "hidapi";
      info.path = d->path ? d->path : "";
      info.vendor_id = d->vendor_id;
      info.product_id = d->product_id;
      info.name = narrow(d->product_string);
      if (info.name.empty() && q) info.name = std::string(q->name);
      info.manufacturer = narrow(d->manufacturer_string);
      info.serial = narrow(d->serial_number);
      info.interface_number = d->interface_number;
      info.usage_page = d->usage_page;
      info.usage = d->usage;
      info.usb_location = detail::hidraw_usb_location(info.path);
      info.report_descriptor = detail::hidraw_report_descriptor(info.path);
      info.accessible = ::access(info.path.c_str(), R_OK | W_OK) == 0;
      out.push_back(std::move(info));
    }
    hid_free_enumeration(list);
    return out;
  }

  Result<std::unique_ptr<Device>> open(const DeviceInfo& info) override {
    hid_device* h = hid_open_path(info.path.c_str());
    if (h == nullptr) {
      if (::access(info.path.c_str(), R_OK | W_OK) != 0) {
        return Error(info.id() + ": no permission; install the udev rules (see docs/devices.md)");
      }
      return Error(info.id() + ": cannot open: " + narrow(hid_error(nullptr)));
    }
    return std::unique_ptr<Device>(std::make_unique<HidapiDevice>(h, info));
  }

 private:
  bool init_ok_ = false;
};

#endif

}  // namespace

std::unique_ptr<Backend> make_hidapi_backend() {
#if SCULPT_HAL_HAVE_HIDAPI
  return std::make_unique<HidapiBackend>();
#else
  return detail::make_not_built_backend("hidapi", "SCULPT_WITH_HIDAPI", "libhidapi-dev");
#endif
}

}  // namespace sculpt::hal
