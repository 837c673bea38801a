// The public entry of the Falcon backend: libusb when built, a clear "not
// built" otherwise (as the other transports do, backends/not_built_backend.h).

#include "sculpt/hal/backends/falcon_backend.h"

#include <utility>

#include "falcon_device.h"
#include "falcon_firmware.h"
#include "libusb_ftdi_transport.h"

namespace sculpt::hal {
namespace {

#if !SCULPT_HAL_HAVE_LIBUSB
const char* const kNotBuilt =
    "not built (configure with -DSCULPT_WITH_LIBUSB=ON and libusb-1.0-0-dev installed)";
#endif

}  // namespace

BackendStatus falcon_backend_status() {
#if SCULPT_HAL_HAVE_LIBUSB
  return {};
#else
  return {BackendState::kNotBuilt, kNotBuilt};
#endif
}

Result<std::vector<DeviceInfo>> list_falcons() {
#if SCULPT_HAL_HAVE_LIBUSB
  return falcon::list_falcons_libusb();
#else
  return Error(std::string("falcon: ") + kNotBuilt);
#endif
}

Result<std::unique_ptr<ForceDevice>> open_falcon(const FalconOptions& options) {
#if SCULPT_HAL_HAVE_LIBUSB
  falcon::FalconOpenOptions open_options;
  open_options.firmware_options.attempts = options.firmware_attempts;
  if (!options.firmware.empty()) {
    open_options.firmware = options.firmware;
  } else if (!options.firmware_path.empty()) {
    auto bytes = falcon::read_falcon_firmware_file(options.firmware_path);
    if (!bytes.ok()) return bytes.error();
    open_options.firmware = std::move(bytes).value();
  }
  DeviceInfo info;
  auto transport = falcon::open_falcon_libusb(options.path, info);
  if (!transport.ok()) return transport.error();
  auto device =
      falcon::FalconDevice::open(std::move(transport).value(), std::move(info), open_options);
  if (!device.ok()) return device.error();
  return std::unique_ptr<ForceDevice>(std::move(device).value());
#else
  return Error("falcon:" + options.path + ": " + kNotBuilt);
#endif
}

}  // namespace sculpt::hal
