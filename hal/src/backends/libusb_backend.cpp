// libusb backend.
// Implements: enumeration of the known 3Dconnexion IDs (their HID interface),
// open with the kernel's usbhid driver detached (re-attached on close),
// HID report descriptor by GET_DESCRIPTOR, synchronous interrupt-IN reads
// with timeout, removal on LIBUSB_ERROR_NO_DEVICE, hotplug arrival/departure
// through libusb's hotplug API (changed()).
// Lacks: unknown controllers (their usage needs the descriptor, read by the
// hidapi backend without opening), output reports.

#include "sculpt/hal/backends/libusb_backend.h"

#include "backends/libusb_names.h"
#include "backends/not_built_backend.h"

#if SCULPT_HAL_HAVE_LIBUSB
#include <libusb.h>

#include <atomic>
#include <cstdio>
#include <cstring>
#include <string>

#include "sculpt/hal/types/clock.h"
#include "sculpt/hal/types/quirks.h"
#endif

namespace sculpt::hal {
namespace {

#if SCULPT_HAL_HAVE_LIBUSB

constexpr uint8_t kHidClass = 3;

std::string path_of(libusb_device* dev, int interface) {
  return usb_location(dev) + ":" + std::to_string(interface);
}

class LibusbDevice final : public Device {
 public:
  LibusbDevice(libusb_device_handle* h, int interface, uint8_t endpoint, uint16_t max_packet,
               bool reattach, DeviceInfo info)
      : handle_(h),
        interface_(interface),
        endpoint_(endpoint),
        max_packet_(max_packet),
        reattach_(reattach),
        info_(std::move(info)) {}
  ~LibusbDevice() override {
    libusb_release_interface(handle_, interface_);
    // Give the device back to usbhid so other programs (and hidraw) see it again.
    if (reattach_) libusb_attach_kernel_driver(handle_, interface_);
    libusb_close(handle_);
  }
  const DeviceInfo& info() const override { return info_; }

  ReadResult read(RawEvent& out, int timeout_ms) override {
    if (gone_) {
      out = RawEvent::removed(monotonic_ns());
      return ReadResult::kRemoved;
    }
    uint8_t buf[512];
    int got = 0;
    // libusb reads 0 as "no timeout"; 1 ms is the shortest wait it has.
    const int r =
        libusb_interrupt_transfer(handle_, endpoint_, buf, std::min<int>(max_packet_, sizeof buf),
                                  &got, static_cast<unsigned>(std::max(timeout_ms, 1)));
    const int64_t t = monotonic_ns();
    if (r == LIBUSB_ERROR_TIMEOUT && got == 0) return ReadResult::kTimeout;
    if (r == LIBUSB_ERROR_NO_DEVICE || r == LIBUSB_ERROR_IO || r == LIBUSB_ERROR_PIPE) {
      gone_ = true;
      out = RawEvent::removed(t);
      return ReadResult::kRemoved;
    }
    if ((r != 0 && r != LIBUSB_ERROR_TIMEOUT) || got <= 0) return ReadResult::kTimeout;
    out = RawEvent::report(t, std::span<const uint8_t>(buf, static_cast<size_t>(got)));
    return ReadResult::kEvent;
  }

 private:
  libusb_device_handle* handle_;
  int interface_;
  uint8_t endpoint_;
  uint16_t max_packet_;
  bool reattach_;
  DeviceInfo info_;
  bool gone_ = false;
};

class LibusbBackend final : public Backend {
 public:
  LibusbBackend() {
    init_result_ = libusb_init(&ctx_);
    if (init_result_ != 0) {
      ctx_ = nullptr;
      return;
    }
    if (libusb_has_capability(LIBUSB_CAP_HAS_HOTPLUG)) {
      const int r = libusb_hotplug_register_callback(
          ctx_, LIBUSB_HOTPLUG_EVENT_DEVICE_ARRIVED | LIBUSB_HOTPLUG_EVENT_DEVICE_LEFT,
          LIBUSB_HOTPLUG_NO_FLAGS, LIBUSB_HOTPLUG_MATCH_ANY, LIBUSB_HOTPLUG_MATCH_ANY,
          LIBUSB_HOTPLUG_MATCH_ANY, &LibusbBackend::on_hotplug, this, &hotplug_handle_);
      hotplug_ = r == LIBUSB_SUCCESS;
    }
  }
  ~LibusbBackend() override {
    if (ctx_ == nullptr) return;
    if (hotplug_) libusb_hotplug_deregister_callback(ctx_, hotplug_handle_);
    libusb_exit(ctx_);
  }
  std::string_view name() const override { return "libusb"; }
  BackendStatus status() override {
    if (ctx_ == nullptr) {
      return {BackendState::kUnavailable, std::string("libusb_init failed: ") +
                                              libusb_error_name(init_result_) +
                                              " (no /dev/bus/usb?)"};
    }
    return {};
  }

  bool changed() override {
    if (!hotplug_) return true;
    // Hotplug callbacks run inside libusb's event handling; give it a turn.
    timeval zero{0, 0};
    libusb_handle_events_timeout_completed(ctx_, &zero, nullptr);
    return changed_.exchange(false);
  }

  Result<std::vector<DeviceInfo>> enumerate() override {
    if (ctx_ == nullptr) return Error(std::string("libusb: ") + status().note);
    libusb_device** list = nullptr;
    const ssize_t n = libusb_get_device_list(ctx_, &list);
    if (n < 0)
      return Error(std::string("libusb: cannot list devices: ") +
                   libusb_error_name(static_cast<int>(n)));
    std::vector<DeviceInfo> out;
    for (ssize_t i = 0; i < n; ++i) {
      libusb_device* dev = list[i];
      libusb_device_descriptor desc{};
      if (libusb_get_device_descriptor(dev, &desc) != 0) continue;
      const DeviceQuirks* q = find_quirks(desc.idVendor, desc.idProduct);
      if (q == nullptr || q->kind == QuirkKind::kIgnore) continue;
      const int interface = hid_interface(dev, nullptr, nullptr);
      if (interface < 0) continue;
      DeviceInfo info;
      info.backend = "libusb";
      info.path = path_of(dev, interface);
      info.vendor_id = desc.idVendor;
      info.product_id = desc.idProduct;
      info.name = std::string(q->name);
      info.interface_number = interface;
      info.usb_location = usb_location(dev);
      // Reading strings (serial) needs an open handle: done only when the
      // node is accessible, and cheap.
      libusb_device_handle* h = nullptr;
      const int opened = libusb_open(dev, &h);
      if (opened == 0) {
        info.serial = usb_string_descriptor(h, desc.iSerialNumber);
        const std::string product = usb_string_descriptor(h, desc.iProduct);
        if (!product.empty()) info.name = product;
        info.manufacturer = usb_string_descriptor(h, desc.iManufacturer);
        libusb_close(h);
      } else if (opened == LIBUSB_ERROR_ACCESS) {
        info.accessible = false;
      }
      out.push_back(std::move(info));
    }
    libusb_free_device_list(list, 1);
    return out;
  }

  Result<std::unique_ptr<Device>> open(const DeviceInfo& info) override {
    if (ctx_ == nullptr) return Error(info.id() + ": " + status().note);
    libusb_device** list = nullptr;
    const ssize_t n = libusb_get_device_list(ctx_, &list);
    if (n < 0) return Error(info.id() + ": cannot list devices");
    libusb_device* found = nullptr;
    int interface = -1;
    uint8_t endpoint = 0;
    uint16_t max_packet = 0;
    for (ssize_t i = 0; i < n && found == nullptr; ++i) {
      const int itf = hid_interface(list[i], &endpoint, &max_packet);
      if (itf >= 0 && path_of(list[i], itf) == info.path) {
        found = list[i];
        interface = itf;
      }
    }
    libusb_device_handle* h = nullptr;
    const int r = found ? libusb_open(found, &h) : LIBUSB_ERROR_NO_DEVICE;
    libusb_free_device_list(list, 1);
    if (r == LIBUSB_ERROR_ACCESS) {
      return Error(info.id() + ": no permission; install the udev rules (see docs/devices.md)");
    }
    if (r != 0) return Error(info.id() + ": cannot open: " + libusb_error_name(r));
    bool reattach = false;
    if (libusb_kernel_driver_active(h, interface) == 1) {
      if (const int d = libusb_detach_kernel_driver(h, interface); d != 0) {
        libusb_close(h);
        return Error(info.id() + ": cannot detach the kernel driver: " + libusb_error_name(d));
      }
      reattach = true;
    }
    if (const int c = libusb_claim_interface(h, interface); c != 0) {
      if (reattach) libusb_attach_kernel_driver(h, interface);
      libusb_close(h);
      return Error(info.id() + ": cannot claim interface " + std::to_string(interface) + ": " +
                   libusb_error_name(c));
    }
    DeviceInfo opened = info;
    // GET_DESCRIPTOR(Report) on the interface: standard request to an interface.
    uint8_t desc[4096];
    const int got = libusb_control_transfer(
        h, static_cast<uint8_t>(int{LIBUSB_ENDPOINT_IN} | int{LIBUSB_RECIPIENT_INTERFACE}),
        LIBUSB_REQUEST_GET_DESCRIPTOR, (LIBUSB_DT_REPORT << 8), static_cast<uint16_t>(interface),
        desc, sizeof desc, 1000);
    if (got > 0) opened.report_descriptor.assign(desc, desc + got);
    return std::unique_ptr<Device>(std::make_unique<LibusbDevice>(
        h, interface, endpoint, max_packet, reattach, std::move(opened)));
  }

 private:
  static int LIBUSB_CALL on_hotplug(libusb_context*, libusb_device*, libusb_hotplug_event,
                                    void* self) {
    static_cast<LibusbBackend*>(self)->changed_.store(true);
    return 0;  // stay registered
  }

  // The first HID interface with an interrupt-IN endpoint; its endpoint
  // address and packet size through the out parameters.
  static int hid_interface(libusb_device* dev, uint8_t* endpoint, uint16_t* max_packet) {
    libusb_config_descriptor* cfg = nullptr;
    if (libusb_get_active_config_descriptor(dev, &cfg) != 0 &&
        libusb_get_config_descriptor(dev, 0, &cfg) != 0) {
      return -1;
    }
    int found = -1;
    for (int i = 0; i < cfg->bNumInterfaces && found < 0; ++i) {
      for (int a = 0; a < cfg->interface[i].num_altsetting && found < 0; ++a) {
        const libusb_interface_descriptor& d = cfg->interface[i].altsetting[a];
        if (d.bInterfaceClass != kHidClass) continue;
        for (int e = 0; e < d.bNumEndpoints; ++e) {
          const libusb_endpoint_descriptor& ep = d.endpoint[e];
          if ((ep.bEndpointAddress & LIBUSB_ENDPOINT_IN) &&
              (ep.bmAttributes & LIBUSB_TRANSFER_TYPE_MASK) == LIBUSB_TRANSFER_TYPE_INTERRUPT) {
            found = d.bInterfaceNumber;
            if (endpoint) *endpoint = ep.bEndpointAddress;
            if (max_packet) *max_packet = ep.wMaxPacketSize;
            break;
          }
        }
      }
    }
    libusb_free_config_descriptor(cfg);
    return found;
  }

  libusb_context* ctx_ = nullptr;
  int init_result_ = 0;
  bool hotplug_ = false;
  libusb_hotplug_callback_handle hotplug_handle_{};
  std::atomic<bool> changed_{true};
};

#endif

}  // namespace

std::unique_ptr<Backend> make_libusb_backend() {
#if SCULPT_HAL_HAVE_LIBUSB
  return std::make_unique<LibusbBackend>();
#else
  return detail::make_not_built_backend("libusb", "SCULPT_WITH_LIBUSB", "libusb-1.0-0-dev");
#endif
}

}  // namespace sculpt::hal
