// Listing: sysfs to skip the nodes without force feedback and to describe
// the ones this user may not open, the device itself for the rest.

#include "evdev_enumeration.h"

#include <array>
#include <cerrno>

namespace sculpt::hal::evdev_ff {
namespace {

DeviceInfo describe(const std::string& node) {
  DeviceInfo info;
  info.backend = "evdev-ff";
  info.path = node;
  return info;
}

// Asks the open node; nullopt when it cannot play FF_CONSTANT or stops answering.
std::optional<DeviceInfo> ask_device(EvdevIo& io, const std::string& node) {
  std::array<uint8_t, (EV_CNT + 7) / 8> ev{};
  std::array<uint8_t, (FF_CNT + 7) / 8> ff{};
  if (io.get_bits(0, ev) < 0 || !evdev_bit(ev, EV_FF)) return std::nullopt;
  if (io.get_bits(EV_FF, ff) < 0 || !evdev_bit(ff, FF_CONSTANT)) return std::nullopt;
  input_id id{};
  DeviceInfo info = describe(node);
  if (io.get_id(id) < 0 || io.get_name(info.name) < 0) return std::nullopt;
  info.vendor_id = id.vendor;
  info.product_id = id.product;
  return info;
}

}  // namespace

Result<std::vector<DeviceInfo>> list_evdev_force_devices(EvdevIo& io) {
  std::vector<DeviceInfo> found;
  for (const std::string& node : io.list_event_nodes()) {
    const std::optional<EvdevSysfs> sys = io.sysfs(node);
    if (sys && !sysfs_bitmap_bit(sys->ff_bitmap, FF_CONSTANT)) continue;
    const int r = io.open(node);
    if (r == -EACCES || r == -EPERM) {
      // Without sysfs nothing says this node has force feedback: leave it
      // out rather than list every keyboard the user may not open.
      if (!sys) continue;
      DeviceInfo info = describe(node);
      info.name = sys->name;
      info.vendor_id = sys->vendor_id;
      info.product_id = sys->product_id;
      info.usb_location = sys->usb_location;
      info.accessible = false;
      found.push_back(std::move(info));
      continue;
    }
    if (r < 0) continue;  // gone since the directory was read
    std::optional<DeviceInfo> info = ask_device(io, node);
    io.close();
    if (!info) continue;
    if (sys) info->usb_location = sys->usb_location;
    found.push_back(std::move(*info));
  }
  return found;
}

}  // namespace sculpt::hal::evdev_ff
