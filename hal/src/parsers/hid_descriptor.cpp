// HID 1.11 §6.2.2: short items are a prefix byte (size in bits 0-1, type in
// bits 2-3, tag in bits 4-7) and 0, 1, 2 or 4 data bytes; long items (0xFE)
// carry a length byte and are skipped. Global state (usage page, logical
// range, report size/count/id) persists across main items and has a
// push/pop stack; local state (usages) is cleared after every main item.

#include "sculpt/hal/parsers/hid_descriptor.h"

#include <climits>
#include <map>
#include <string>

#include "sculpt/hal/types/raw_event.h"

namespace sculpt::hal {
namespace {

struct Globals {
  uint16_t usage_page = 0;
  int32_t logical_min = 0;
  int32_t logical_max = 0;
  uint32_t report_size = 0;
  uint32_t report_count = 0;
  uint8_t report_id = 0;
};

constexpr uint16_t kGenericDesktop = 0x01;
constexpr uint16_t kButtonPage = 0x09;
constexpr uint16_t kUsageX = 0x30;
constexpr uint16_t kUsageRz = 0x35;
// 4 KiB: a high-speed HID interrupt packet is at most 1 KiB.
constexpr uint64_t kMaxReportBits = 4096 * 8;
// Fields a report event can hold (RawEvent keeps 64 bytes, the Report ID
// byte among them): fields past it are never read, so they are not kept.
constexpr uint64_t kReadableBits = RawEvent::kMaxReportBytes * 8;
// Button usages the parser reports (std::bitset<128> of buttons).
constexpr uint16_t kMaxButtonUsage = 128;
// Every report walks the button fields: a bound keeps that microseconds
// whatever a (hostile) descriptor declares.
constexpr size_t kMaxButtonFields = 1024;

Error at(size_t offset, const std::string& what) {
  return Error("report descriptor: byte " + std::to_string(offset) + ": " + what);
}

}  // namespace

bool HidLayout::is_multi_axis_controller() const {
  if (usage_page != kGenericDesktop || usage != 0x08) return false;
  for (const auto& a : axes) {
    if (a) return true;
  }
  return false;
}

Result<HidLayout> parse_hid_descriptor(std::span<const uint8_t> d) {
  HidLayout layout;
  Globals g;
  std::vector<Globals> stack;
  std::vector<uint32_t> usages;  // extended: page << 16 | usage
  uint32_t usage_min = 0, usage_max = 0;
  bool have_range = false;
  std::map<uint8_t, uint32_t> bits_per_report;
  int depth = 0;
  bool have_application = false;

  size_t i = 0;
  while (i < d.size()) {
    const size_t item_at = i;
    const uint8_t prefix = d[i++];
    if (prefix == 0xFE) {  // long item
      if (i + 2 > d.size()) return at(item_at, "long item runs past the end");
      i += 2 + d[i];
      if (i > d.size()) return at(item_at, "long item runs past the end");
      continue;
    }
    const size_t size = (prefix & 3) == 3 ? 4 : (prefix & 3);
    const int type = (prefix >> 2) & 3;
    const int tag = prefix >> 4;
    if (i + size > d.size()) return at(item_at, "item runs past the end");
    uint32_t u = 0;
    for (size_t k = 0; k < size; ++k)
      u |= uint32_t{d[i + k]} << (8 * k);
    int32_t s = static_cast<int32_t>(u);
    if (size == 1) s = static_cast<int8_t>(u);
    if (size == 2) s = static_cast<int16_t>(u);
    i += size;

    if (type == 1) {  // global
      switch (tag) {
        case 0x0:
          g.usage_page = static_cast<uint16_t>(u);
          break;
        case 0x1:
          g.logical_min = s;
          break;
        case 0x2:
          g.logical_max = s;
          break;
        case 0x7:
          g.report_size = u;
          break;
        case 0x8:
          if (u == 0 || u > 255)
            return at(item_at, "report id " + std::to_string(u) + " out of 1..255");
          g.report_id = static_cast<uint8_t>(u);
          layout.numbered_reports = true;
          break;
        case 0x9:
          g.report_count = u;
          break;
        case 0xA:
          stack.push_back(g);
          break;
        case 0xB:
          if (stack.empty()) return at(item_at, "pop without push");
          g = stack.back();
          stack.pop_back();
          break;
        default:
          break;  // physical range, units: not needed for deflection
      }
      continue;
    }
    if (type == 2) {  // local
      const uint32_t full = size == 4 ? u : (uint32_t{g.usage_page} << 16) | (u & 0xFFFF);
      switch (tag) {
        case 0x0:
          usages.push_back(full);
          break;
        case 0x1:
          usage_min = full;
          have_range = true;
          break;
        case 0x2:
          usage_max = full;
          have_range = true;
          break;
        default:
          break;
      }
      continue;
    }
    if (type != 0) return at(item_at, "reserved item type");
    // Main items.
    switch (tag) {
      case 0xA: {  // collection
        ++depth;
        if (u == 1 && !have_application) {  // application
          const uint32_t use = usages.empty() ? (have_range ? usage_min : 0) : usages.front();
          layout.usage_page = static_cast<uint16_t>(use >> 16);
          layout.usage = static_cast<uint16_t>(use & 0xFFFF);
          have_application = true;
        }
        break;
      }
      case 0xC:
        if (depth == 0) return at(item_at, "end collection without collection");
        --depth;
        break;
      case 0x8: {  // input
        // Constant fields are padding and may be any size; data fields are read as 32-bit values.
        if (!(u & 1) && g.report_count != 0 && (g.report_size == 0 || g.report_size > 32)) {
          return at(item_at,
                    "input field size " + std::to_string(g.report_size) + " bits out of 1..32");
        }
        uint32_t& bits = bits_per_report[g.report_id];
        const bool constant = (u & 1) != 0;
        const bool variable = (u & 2) != 0;
        const bool relative = (u & 4) != 0;
        // A report longer than any transport carries is a broken (or hostile)
        // descriptor; checking here also bounds the loop below.
        const uint64_t total = uint64_t{bits} + uint64_t{g.report_size} * g.report_count;
        if (total > kMaxReportBits) {
          return at(item_at, "report " + std::to_string(g.report_id) + " grows to " +
                                 std::to_string(total) + " bits, more than " +
                                 std::to_string(kMaxReportBits));
        }
        if (constant || !variable) {
          // Padding, or an array input (key codes): no axis or button of ours.
          bits = static_cast<uint32_t>(total);
          break;
        }
        for (uint32_t k = 0; k < g.report_count; ++k) {
          uint32_t use = 0;
          if (!usages.empty()) {
            use = usages[std::min<size_t>(k, usages.size() - 1)];
          } else if (have_range && usage_min + k <= usage_max) {
            use = usage_min + k;
          }
          HidField f;
          f.report_id = g.report_id;
          f.bit_offset = bits;
          f.bit_size = g.report_size;
          f.logical_min = g.logical_min;
          f.logical_max = g.logical_max;
          // A one-byte 0xFF maximum with a non-negative minimum means 255
          // (descriptors in the wild rely on it).
          if (g.logical_min >= 0 && g.logical_max < 0) {
            f.logical_max =
                g.report_size < 32 ? static_cast<int32_t>((1u << g.report_size) - 1) : INT32_MAX;
          }
          f.relative = relative;
          f.usage_page = static_cast<uint16_t>(use >> 16);
          f.usage = static_cast<uint16_t>(use & 0xFFFF);
          if (f.usage_page == kGenericDesktop && f.usage >= kUsageX && f.usage <= kUsageRz) {
            auto& slot = layout.axes[f.usage - kUsageX];
            if (!slot) slot = f;  // the first field of an axis wins
          } else if (f.usage_page == kButtonPage && f.usage >= 1 && f.usage <= kMaxButtonUsage &&
                     uint64_t{f.bit_offset} + f.bit_size <= kReadableBits) {
            if (layout.buttons.size() == kMaxButtonFields) {
              return at(item_at,
                        "more than " + std::to_string(kMaxButtonFields) + " button fields");
            }
            layout.buttons.push_back(f);
          }
          bits += g.report_size;
        }
        break;
      }
      default:
        break;  // output, feature
    }
    usages.clear();
    have_range = false;
  }
  if (depth != 0)
    return Error("report descriptor: " + std::to_string(depth) + " collection(s) not closed");
  return layout;
}

std::optional<int32_t> extract_hid_field(std::span<const uint8_t> data, const HidField& f) {
  if (f.bit_size == 0 || f.bit_size > 32) return std::nullopt;
  const uint64_t end = uint64_t{f.bit_offset} + f.bit_size;
  if (end > uint64_t{data.size()} * 8) return std::nullopt;
  uint64_t v = 0;
  for (uint32_t k = 0; k < f.bit_size; ++k) {
    const uint32_t bit = f.bit_offset + k;
    v |= uint64_t((data[bit / 8] >> (bit % 8)) & 1) << k;
  }
  if (f.logical_min < 0 && f.bit_size < 32 && (v >> (f.bit_size - 1)) & 1) {
    v |= ~uint64_t{0} << f.bit_size;  // sign-extend
  }
  return static_cast<int32_t>(static_cast<uint32_t>(v));
}

}  // namespace sculpt::hal
