// The quirks table. Product IDs after spacenavd's usbdb and the Linux
// hid-ids list; layouts after what the devices send (older 046d devices split
// translation and rotation into reports 1 and 2, the 256f generation sends
// one 13-byte report 1).

#include "sculpt/hal/types/quirks.h"

#include <algorithm>
#include <array>

namespace sculpt::hal {
namespace {

// The SpaceMouse Pro family reports its 15 buttons sparsely in a 32-bit mask
// (menu, fit, the view keys, 1..4, Esc/Alt/Shift/Ctrl, rotation lock); map the
// used bits to logical buttons 0..14, in the order of the bits.
constexpr std::array<uint8_t, 32> kProButtons = {
    0,   1,   255, 255, 2,   3,   255, 255, 4,  255, 255, 255, 5,   6,   7,   8,
    255, 255, 255, 255, 255, 255, 9,   10,  11, 12,  13,  14,  255, 255, 255, 255};

constexpr DeviceQuirks mouse(uint16_t vid, uint16_t pid, std::string_view name, MotionLayout layout,
                             ButtonForm buttons = ButtonForm::kBitmask, bool battery = false) {
  DeviceQuirks q;
  q.vendor_id = vid;
  q.product_id = pid;
  q.name = name;
  q.layout = layout;
  q.buttons = buttons;
  q.has_battery = battery;
  return q;
}

constexpr DeviceQuirks ignore(uint16_t vid, uint16_t pid, std::string_view name) {
  DeviceQuirks q;
  q.vendor_id = vid;
  q.product_id = pid;
  q.name = name;
  q.kind = QuirkKind::kIgnore;
  return q;
}

constexpr DeviceQuirks with_buttons(DeviceQuirks q, std::span<const uint8_t> map) {
  q.button_map = map;
  return q;
}

constexpr DeviceQuirks receiver(DeviceQuirks q) {
  q.multi_axis_interface_only = true;
  return q;
}

constexpr MotionLayout kSplit = MotionLayout::kSplit;
constexpr MotionLayout kCombined = MotionLayout::kCombined;

// Sorted by vendor, product (find_quirks searches it).
constexpr std::array kQuirks = {
    mouse(0x046d, 0xc603, "SpaceMouse Plus XT USB", kSplit),
    mouse(0x046d, 0xc605, "CADman", kSplit),
    mouse(0x046d, 0xc606, "SpaceMouse Classic USB", kSplit),
    mouse(0x046d, 0xc621, "SpaceBall 5000 USB", kSplit),
    mouse(0x046d, 0xc623, "SpaceTraveler", kSplit),
    mouse(0x046d, 0xc625, "SpacePilot", kSplit),
    mouse(0x046d, 0xc626, "SpaceNavigator", kSplit),
    mouse(0x046d, 0xc627, "SpaceExplorer", kSplit),
    mouse(0x046d, 0xc628, "SpaceNavigator for Notebooks", kSplit),
    mouse(0x046d, 0xc629, "SpacePilot Pro", kSplit),
    with_buttons(mouse(0x046d, 0xc62b, "SpaceMouse Pro", kSplit), kProButtons),
    mouse(0x256f, 0xc62e, "SpaceMouse Wireless (cable)", kCombined),
    mouse(0x256f, 0xc62f, "SpaceMouse Wireless (receiver)", kCombined, ButtonForm::kBitmask, true),
    with_buttons(mouse(0x256f, 0xc631, "SpaceMouse Pro Wireless (cable)", kCombined), kProButtons),
    with_buttons(mouse(0x256f, 0xc632, "SpaceMouse Pro Wireless (receiver)", kCombined,
                       ButtonForm::kBitmask, true),
                 kProButtons),
    mouse(0x256f, 0xc633, "SpaceMouse Enterprise", kCombined, ButtonForm::kNumbered),
    mouse(0x256f, 0xc635, "SpaceMouse Compact", kCombined),
    mouse(0x256f, 0xc636, "SpaceMouse Module", kCombined),
    ignore(0x256f, 0xc650, "CadMouse"),
    ignore(0x256f, 0xc651, "CadMouse Wireless"),
    // The Universal Receiver presents a mouse and a keyboard interface beside
    // the 6-DOF one; only the multi-axis interface is opened.
    receiver(mouse(0x256f, 0xc652, "Universal Receiver", kCombined, ButtonForm::kBitmask, true)),
    ignore(0x256f, 0xc654, "CadMouse Pro Wireless"),
    ignore(0x256f, 0xc655, "CadMouse Compact"),
    ignore(0x256f, 0xc656, "CadMouse Pro Wireless Left"),
    ignore(0x256f, 0xc657, "CadMouse Compact Wireless"),
    ignore(0x256f, 0xc664, "Keyboard Pro"),
    ignore(0x256f, 0xc665, "Numpad Pro"),
};

constexpr bool sorted() {
  for (size_t i = 1; i < kQuirks.size(); ++i) {
    const auto a = (uint32_t{kQuirks[i - 1].vendor_id} << 16) | kQuirks[i - 1].product_id;
    const auto b = (uint32_t{kQuirks[i].vendor_id} << 16) | kQuirks[i].product_id;
    if (a >= b) return false;
  }
  return true;
}
static_assert(sorted(), "kQuirks must be sorted by vendor:product and unique");

}  // namespace

const DeviceQuirks* find_quirks(uint16_t vendor_id, uint16_t product_id) {
  const auto key = (uint32_t{vendor_id} << 16) | product_id;
  const auto it =
      std::lower_bound(kQuirks.begin(), kQuirks.end(), key, [](const DeviceQuirks& q, uint32_t k) {
        return ((uint32_t{q.vendor_id} << 16) | q.product_id) < k;
      });
  if (it == kQuirks.end() || it->vendor_id != vendor_id || it->product_id != product_id)
    return nullptr;
  return &*it;
}

std::span<const DeviceQuirks> all_quirks() {
  return kQuirks;
}

bool is_ignored(uint16_t vendor_id, uint16_t product_id, uint16_t usage_page, uint16_t usage) {
  const DeviceQuirks* q = find_quirks(vendor_id, product_id);
  if (q == nullptr) return false;
  if (q->kind == QuirkKind::kIgnore) return true;
  const bool usage_known = usage_page != 0;
  return q->multi_axis_interface_only && usage_known && !(usage_page == 1 && usage == 8);
}

}  // namespace sculpt::hal
