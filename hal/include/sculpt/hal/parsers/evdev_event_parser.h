#pragma once
// The parser for Linux evdev 6-axis devices (backends/evdev_backend.h), and
// the two byte forms a session records for them:
//
// - the layout, in DeviceInfo::report_descriptor: which of the six axes
//   (X Y Z RX RY RZ, codes 0..5 of EV_ABS and of EV_REL alike) are absolute
//   and their range, which are relative and their full scale, and the key
//   codes that are buttons (button i = button_codes[i]);
// - the events, in kReport RawEvents: 1..8 records of 8 bytes each, the
//   type, code and value of one struct input_event (little-endian u16, u16,
//   s32; the kernel's timestamp is left out, the RawEvent has the arrival
//   time). Portable across word sizes, unlike struct input_event itself.
//
// Semantics are the kernel's (Documentation/input/event-codes.rst): values
// change at SYN_REPORT, so one frame gives at most one kMotion (then its
// button changes, in code order of arrival); after SYN_DROPPED everything up
// to and including the next SYN_REPORT is dropped (the backend then records
// a frame with the device's whole state, so a replay resyncs the same way).
// A relative axis is a deflection reported each frame; one absent from a
// frame is 0 (the kernel never passes a relative 0 on).
//
// Axes go into the station frame like a HID multi-axis controller's: evdev
// passes the HID usages X..RZ through unchanged (+Y toward the user, +Z
// down), so DeviceQuirks' axis_source/axis_sign apply (the device's row when
// known, else the default row). Absolute axes are scaled by their range to
// [-1, 1], relative ones by their full scale, both clamped.
//
// Bad bytes (a report whose size is not a whole number of records, a layout
// that does not decode) are counted and dropped, never thrown.

#include <array>
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "sculpt/hal/parsers/report_parser.h"
#include "sculpt/hal/types/quirks.h"

namespace sculpt::hal {

enum class EvdevAxisKind : uint8_t {
  kAbsolute = 1,  ///< EV_ABS: a position in [minimum, maximum]
  kRelative = 2,  ///< EV_REL: a deflection per frame, full scale at +-maximum
};

struct EvdevAxisRange {
  EvdevAxisKind kind = EvdevAxisKind::kAbsolute;
  int32_t minimum = -350;  ///< kAbsolute only
  int32_t maximum = 350;   ///< kAbsolute: the top of the range; kRelative: full scale (> 0)
};

/// What the parser needs to know of the device, recorded with the session.
struct EvdevLayout {
  static constexpr size_t kMaxButtons = 32;
  std::array<EvdevAxisRange, 6> axes{};  ///< X Y Z RX RY RZ
  std::vector<uint16_t> button_codes;    ///< key codes; button i is button_codes[i]
};

/// One input_event without its time.
struct EvdevRecord {
  uint16_t type = 0;
  uint16_t code = 0;
  int32_t value = 0;
};

inline constexpr size_t kEvdevRecordBytes = 8;
inline constexpr size_t kEvdevRecordsPerReport = 8;  ///< 64 bytes: RawEvent::kMaxReportBytes

enum class EvdevLayoutError : uint8_t {
  kNone,
  kBadMagic,        ///< not "EVD1"
  kShort,           ///< ends inside the layout
  kBadAxis,         ///< unknown kind, an empty absolute range, a relative scale <= 0
  kTooManyButtons,  ///< more than kMaxButtons
  kLong,            ///< bytes after the layout
};

/// "not an evdev layout (magic)" ...; never empty.
std::string_view describe(EvdevLayoutError error);

/// "EVD1", then per axis kind u8, minimum s32, maximum s32, then the button
/// count u8 and each code u16; little-endian. At most 4 + 54 + 1 + 64 bytes.
std::vector<uint8_t> encode_evdev_layout(const EvdevLayout& layout);
/// Decodes a whole layout; `out` is only written on kNone.
EvdevLayoutError decode_evdev_layout(std::span<const uint8_t> bytes, EvdevLayout& out);

/// Writes kEvdevRecordBytes bytes at `out`.
void encode_evdev_record(const EvdevRecord& record, uint8_t* out);
/// Reads kEvdevRecordBytes bytes at `in`.
EvdevRecord decode_evdev_record(const uint8_t* in);

class EvdevEventParser final : public ReportParser {
 public:
  /// quirks: the device's row of the quirks table, or nullptr for the default mapping.
  explicit EvdevEventParser(EvdevLayout layout, const DeviceQuirks* quirks = nullptr);
  void parse(const RawEvent& event, std::vector<InputEvent>& out) override;

  /// SYN_DROPPED records seen (the kernel's queue overran).
  int64_t overruns() const { return overruns_; }

 private:
  void take(const EvdevRecord& r, int64_t t_ns, std::vector<InputEvent>& out);
  void end_frame(int64_t t_ns, std::vector<InputEvent>& out);
  int button_index(uint16_t code) const;

  EvdevLayout layout_;
  DeviceQuirks mapping_;
  std::array<int32_t, 6> value_{};  // per evdev axis, as of the last frame
  std::array<int32_t, 6> pending_{};
  bool axes_touched_ = false;  // the pending frame moved an axis
  uint32_t buttons_ = 0;       // as of the last frame
  uint32_t pending_buttons_ = 0;
  std::vector<int> button_order_;  // buttons changed in the pending frame, in arrival order
  bool dropping_ = false;          // after SYN_DROPPED, until SYN_REPORT
  bool has_relative_ = false;
  int64_t overruns_ = 0;
};

}  // namespace sculpt::hal
