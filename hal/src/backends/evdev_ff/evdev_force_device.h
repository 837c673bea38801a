#pragma once
// An evdev force-feedback stick as a ForceDevice (DESIGN.md §5a,
// ForceCapability::kEffectBased), over an EvdevIo.
//
// Force: ONE FF_CONSTANT effect, uploaded and set playing at open, then
// updated in place (EVIOCSFF with its id) by write() whenever its level or
// direction changes, and only then: at 1 kHz most ticks change nothing a
// stick can show, and each update is a USB transfer. The force's x/y (N,
// device frame) become level and direction (constant_effect_mapping.h);
// z is ignored. zero() sets level 0 in place and stops the effect; a later
// write() with force plays it again. The destructor removes the effect
// (EVIOCRMFF, which also stops it) and closes the node.
//
// Position: the stick's ABS_X, ABS_Y and, when present, ABS_Z, each on
// [-1, 1] by its absinfo range, times workspace_half_range_mm:
// x = ABS_X (right +), y = -ABS_Y (a joystick's ABS_Y grows toward the
// user; the device frame's y is up = away from the user), z = ABS_Z as the
// device reports it; an axis the device lacks reads 0. Values change at
// each SYN_REPORT, so a frame is never half applied. Buttons: the device's
// BTN_JOYSTICK..BTN_DIGI-1 codes (BTN_TRIGGER or BTN_SOUTH first), then
// BTN_TRIGGER_HAPPY*, numbered from bit 0 in code order, at most 32.
//
// Errors: ENODEV from any call (the device was unplugged) -> ForceIo::kRemoved
// for good; any other failure -> kFault for that call (counted).
//
// Units: mm, N.

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "constant_effect_mapping.h"
#include "evdev_io.h"
#include "sculpt/base/result.h"
#include "sculpt/hal/backends/evdev_ff_backend.h"
#include "sculpt/hal/force/force_device.h"

namespace sculpt::hal::evdev_ff {

/// What the device sent and what it cost, for a panel or a test.
struct EvdevForceCounters {
  int64_t events = 0;          ///< input_event records read
  int64_t frames = 0;          ///< SYN_REPORTs (frames applied)
  int64_t overruns = 0;        ///< SYN_DROPPED: the kernel's queue overran; state re-read
  int64_t stray_bytes = 0;     ///< bytes read that made no whole input_event (dropped)
  int64_t effect_updates = 0;  ///< EVIOCSFF in place after the first upload
  int64_t io_errors = 0;       ///< failed calls other than ENODEV
};

class EvdevForceDevice final : public ForceDevice {
 public:
  /// Opens `path` through `io`: checks FF_CONSTANT, reads the axes and
  /// buttons, sets FF_GAIN (and FF_AUTOCENTER 0), uploads the effect at
  /// level 0 and plays it. Errors name `path` and the step.
  static Result<std::unique_ptr<EvdevForceDevice>> open(std::unique_ptr<EvdevIo> io,
                                                        const std::string& path,
                                                        const EvdevForceOptions& options = {});
  ~EvdevForceDevice() override;
  EvdevForceDevice(const EvdevForceDevice&) = delete;
  EvdevForceDevice& operator=(const EvdevForceDevice&) = delete;

  const DeviceInfo& info() const override { return info_; }
  const ForceLimits& limits() const override { return limits_; }
  ForceIo read(ForceDeviceState& out) override;
  ForceIo write(glm::vec3 force_n) override;
  void zero() noexcept override;

  /// The id the kernel gave the effect.
  int16_t effect_id() const { return effect_id_; }
  /// The level and direction the device has now.
  const ConstantEffectCommand& effect() const { return sent_; }
  bool playing() const { return playing_; }
  const EvdevForceCounters& counters() const { return counters_; }

 private:
  EvdevForceDevice(std::unique_ptr<EvdevIo> io, const EvdevForceOptions& options);

  static constexpr size_t kAxes = 3;  // ABS_X, ABS_Y, ABS_Z
  static constexpr size_t kMaxButtons = 32;
  struct Axis {
    bool present = false;
    input_absinfo range{};
  };
  struct InputState {
    std::array<int32_t, kAxes> axis{};
    uint32_t buttons = 0;
  };

  // Maps a failed call (-errno); ENODEV marks the device removed for good.
  ForceIo failure(long minus_errno);
  int send_event(uint16_t type, uint16_t code, int32_t value);
  int upload(const ConstantEffectCommand& command);
  void take(const input_event& ev);
  // Re-reads axes and buttons after SYN_DROPPED (0 or -errno).
  int resync();
  int button_bit(uint16_t code) const;

  std::unique_ptr<EvdevIo> io_;
  EvdevForceOptions options_;
  DeviceInfo info_;
  ForceLimits limits_;
  std::array<Axis, kAxes> axes_{};
  std::vector<uint16_t> button_codes_;  // bit i = button_codes_[i]
  InputState pending_;                  // events since the last SYN_REPORT applied
  InputState state_;                    // as of the last SYN_REPORT
  bool dropping_ = false;               // after SYN_DROPPED, until the next SYN_REPORT
  int16_t effect_id_ = -1;
  ConstantEffectCommand sent_;
  bool playing_ = false;
  bool removed_ = false;
  EvdevForceCounters counters_;
  std::array<uint8_t, 64 * sizeof(input_event)> read_buf_{};
};

}  // namespace sculpt::hal::evdev_ff
