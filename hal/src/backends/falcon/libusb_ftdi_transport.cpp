// The libusb-1.0 FtdiTransport. What a real FT232 does that the fake does
// not: an idle IN endpoint still answers every latency period with its two
// status bytes, and a bulk read must ask for a whole 64-byte packet
// (libnifalcon FalconCommLibUSB.cpp issueRead: "Try to read over 64 and
// you'll fry libusb-1.0. Try to read under 64 and you'll fry OS X").

#include "libusb_ftdi_transport.h"
#include "backends/libusb_names.h"

#if SCULPT_HAL_HAVE_LIBUSB
#include <libusb.h>

#include <algorithm>
#include <utility>

namespace sculpt::hal::falcon {
namespace {

constexpr uint16_t kVendor = 0x0403;
constexpr uint16_t kProduct = 0xcb48;
constexpr int kInterface = 0;
constexpr unsigned char kBulkOut = 0x02;
constexpr unsigned char kBulkIn = 0x81;
constexpr unsigned kControlTimeoutMs = 1000;

UsbStatus status_of(int r) {
  if (r >= 0) return UsbStatus::kOk;
  if (r == LIBUSB_ERROR_TIMEOUT) return UsbStatus::kTimeout;
  if (r == LIBUSB_ERROR_NO_DEVICE) return UsbStatus::kNoDevice;
  return UsbStatus::kError;
}

bool is_falcon(libusb_device* dev) {
  libusb_device_descriptor desc{};
  return libusb_get_device_descriptor(dev, &desc) == 0 && desc.idVendor == kVendor &&
         desc.idProduct == kProduct;
}

DeviceInfo describe(libusb_device* dev) {
  DeviceInfo info;
  info.backend = "falcon";
  info.path = usb_location(dev);
  info.usb_location = info.path;
  info.name = "Novint Falcon";
  info.vendor_id = kVendor;
  info.product_id = kProduct;
  info.interface_number = kInterface;
  return info;
}

void read_strings(libusb_device* dev, libusb_device_handle* h, DeviceInfo& info) {
  libusb_device_descriptor desc{};
  if (libusb_get_device_descriptor(dev, &desc) != 0) return;
  info.serial = usb_string_descriptor(h, desc.iSerialNumber);
  info.manufacturer = usb_string_descriptor(h, desc.iManufacturer);
  if (std::string product = usb_string_descriptor(h, desc.iProduct); !product.empty())
    info.name = std::move(product);
}

class LibusbFtdiTransport final : public FtdiTransport {
 public:
  LibusbFtdiTransport(libusb_context* ctx, libusb_device_handle* h, bool reattach)
      : ctx_(ctx), handle_(h), reattach_(reattach) {}
  ~LibusbFtdiTransport() override {
    libusb_release_interface(handle_, kInterface);
    // Give the chip back to ftdi_sio, so /dev/ttyUSB* comes back.
    if (reattach_) libusb_attach_kernel_driver(handle_, kInterface);
    libusb_close(handle_);
    libusb_exit(ctx_);
  }
  LibusbFtdiTransport(const LibusbFtdiTransport&) = delete;
  LibusbFtdiTransport& operator=(const LibusbFtdiTransport&) = delete;

  UsbStatus control(FtdiRequest request, uint16_t value, uint16_t index) override {
    const auto type = static_cast<uint8_t>(int{LIBUSB_REQUEST_TYPE_VENDOR} |
                                           int{LIBUSB_RECIPIENT_DEVICE} | int{LIBUSB_ENDPOINT_OUT});
    return status_of(libusb_control_transfer(handle_, type, static_cast<uint8_t>(request), value,
                                             index, nullptr, 0, kControlTimeoutMs));
  }

  UsbTransfer bulk_write(std::span<const uint8_t> bytes, int timeout_ms) override {
    int done = 0;
    // libusb takes a non-const buffer for both directions; OUT never writes it.
    const int r = libusb_bulk_transfer(handle_, kBulkOut, const_cast<uint8_t*>(bytes.data()),
                                       static_cast<int>(bytes.size()), &done,
                                       static_cast<unsigned>(std::max(timeout_ms, 1)));
    return {status_of(r), static_cast<size_t>(std::max(done, 0))};
  }

  UsbTransfer bulk_read(std::span<uint8_t> buf, int timeout_ms) override {
    int done = 0;
    const int length = static_cast<int>(std::min(buf.size(), kFtdiPacketBytes));
    const int r = libusb_bulk_transfer(handle_, kBulkIn, buf.data(), length, &done,
                                       static_cast<unsigned>(std::max(timeout_ms, 1)));
    return {status_of(r), static_cast<size_t>(std::max(done, 0))};
  }

 private:
  libusb_context* ctx_;
  libusb_device_handle* handle_;
  bool reattach_;
};

}  // namespace

Result<std::vector<DeviceInfo>> list_falcons_libusb() {
  libusb_context* ctx = nullptr;
  if (const int r = libusb_init(&ctx); r != 0)
    return Error(std::string("falcon: libusb_init failed: ") + libusb_error_name(r));
  libusb_device** list = nullptr;
  const ssize_t n = libusb_get_device_list(ctx, &list);
  if (n < 0) {
    libusb_exit(ctx);
    return Error(std::string("falcon: cannot list USB devices: ") +
                 libusb_error_name(static_cast<int>(n)));
  }
  std::vector<DeviceInfo> out;
  for (ssize_t i = 0; i < n; ++i) {
    if (!is_falcon(list[i])) continue;
    DeviceInfo info = describe(list[i]);
    libusb_device_handle* h = nullptr;
    if (const int r = libusb_open(list[i], &h); r == 0) {
      read_strings(list[i], h, info);
      libusb_close(h);
    } else if (r == LIBUSB_ERROR_ACCESS) {
      info.accessible = false;
    }
    out.push_back(std::move(info));
  }
  libusb_free_device_list(list, 1);
  libusb_exit(ctx);
  return out;
}

Result<std::unique_ptr<FtdiTransport>> open_falcon_libusb(const std::string& path,
                                                          DeviceInfo& info) {
  const std::string name = "falcon:" + (path.empty() ? std::string("(first)") : path);
  libusb_context* ctx = nullptr;
  if (const int r = libusb_init(&ctx); r != 0)
    return Error(name + ": libusb_init failed: " + libusb_error_name(r));
  libusb_device** list = nullptr;
  const ssize_t n = libusb_get_device_list(ctx, &list);
  if (n < 0) {
    libusb_exit(ctx);
    return Error(name + ": cannot list USB devices");
  }
  libusb_device* found = nullptr;
  for (ssize_t i = 0; i < n && found == nullptr; ++i) {
    if (is_falcon(list[i]) && (path.empty() || usb_location(list[i]) == path)) found = list[i];
  }
  libusb_device_handle* h = nullptr;
  const int r = found ? libusb_open(found, &h) : LIBUSB_ERROR_NO_DEVICE;
  if (r == 0) {
    info = describe(found);
    read_strings(found, h, info);
  }
  libusb_free_device_list(list, 1);
  auto fail = [&](std::string why) {
    if (h) libusb_close(h);
    libusb_exit(ctx);
    return Error(name + ": " + why);
  };
  if (r == LIBUSB_ERROR_NO_DEVICE) return fail("no Novint Falcon (0403:cb48) there");
  if (r == LIBUSB_ERROR_ACCESS)
    return fail(
        "no permission; install the udev rules (hal/udev/71-sculpt-falcon.rules) and re-plug it");
  if (r != 0) return fail(std::string("cannot open: ") + libusb_error_name(r));
  bool reattach = false;
  if (libusb_kernel_driver_active(h, kInterface) == 1) {
    // ftdi_sio has it as a serial port.
    if (const int d = libusb_detach_kernel_driver(h, kInterface); d != 0)
      return fail(std::string("cannot detach ftdi_sio: ") + libusb_error_name(d));
    reattach = true;
  }
  if (const int c = libusb_claim_interface(h, kInterface); c != 0) {
    if (reattach) libusb_attach_kernel_driver(h, kInterface);
    return fail(std::string("cannot claim interface 0: ") + libusb_error_name(c) +
                " (another program has it?)");
  }
  return std::unique_ptr<FtdiTransport>(std::make_unique<LibusbFtdiTransport>(ctx, h, reattach));
}

}  // namespace sculpt::hal::falcon

#endif  // SCULPT_HAL_HAVE_LIBUSB
