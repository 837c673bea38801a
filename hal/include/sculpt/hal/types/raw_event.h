#pragma once
// What a backend delivers: the bytes of one HID input report, or (for
// spacenavd, which has already decoded the device) an axis, button, sync or
// removal event. Every event carries its arrival time in monotonic ns.

#include <algorithm>
#include <array>
#include <cstdint>
#include <span>

namespace sculpt::hal {

enum class RawEventKind : uint8_t {
  kReport,   ///< bytes(): one input report, report id first when the device numbers its reports
  kAxis,     ///< index 0..5 (tx ty tz rx ry rz in the backend's frame), value in device counts
  kButton,   ///< index = button number from 0, value 1 pressed / 0 released
  kSync,     ///< closes a group of kAxis events: one complete motion sample
  kRemoved,  ///< the device is gone; nothing follows
};

struct RawEvent {
  /// Largest report kept, in bytes (full-speed HID interrupt packets are 64).
  static constexpr size_t kMaxReportBytes = 64;

  RawEventKind kind = RawEventKind::kReport;
  int64_t t_ns = 0;        ///< arrival time, monotonic ns
  uint16_t size = 0;       ///< report bytes used in data
  bool truncated = false;  ///< the device sent more than kMaxReportBytes; the tail was cut
  int32_t index = 0;       ///< kAxis / kButton: which axis or button
  int32_t value = 0;       ///< kAxis: counts; kButton: 1 pressed, 0 released
  std::array<uint8_t, kMaxReportBytes> data{};

  std::span<const uint8_t> bytes() const { return {data.data(), size}; }

  static RawEvent report(int64_t t_ns, std::span<const uint8_t> bytes) {
    RawEvent e;
    e.kind = RawEventKind::kReport;
    e.t_ns = t_ns;
    e.truncated = bytes.size() > kMaxReportBytes;
    e.size = static_cast<uint16_t>(std::min(bytes.size(), kMaxReportBytes));
    std::copy_n(bytes.begin(), e.size, e.data.begin());
    return e;
  }
  static RawEvent axis(int64_t t_ns, int index, int value) {
    RawEvent e;
    e.kind = RawEventKind::kAxis;
    e.t_ns = t_ns;
    e.index = index;
    e.value = value;
    return e;
  }
  static RawEvent button(int64_t t_ns, int index, bool pressed) {
    RawEvent e;
    e.kind = RawEventKind::kButton;
    e.t_ns = t_ns;
    e.index = index;
    e.value = pressed ? 1 : 0;
    return e;
  }
  static RawEvent sync(int64_t t_ns) {
    RawEvent e;
    e.kind = RawEventKind::kSync;
    e.t_ns = t_ns;
    return e;
  }
  static RawEvent removed(int64_t t_ns) {
    RawEvent e;
    e.kind = RawEventKind::kRemoved;
    e.t_ns = t_ns;
    return e;
  }
};

}  // namespace sculpt::hal
