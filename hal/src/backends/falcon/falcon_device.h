#pragma once
// The Novint Falcon as a ForceDevice: the FTDI transport, the firmware, the
// packet and the kinematics put together (DESIGN.md §5a).
//
// One packet exchange per haptic tick: write() sends the motor commands for
// a force; the next read() takes the device's answer (encoders, buttons,
// homed flags) and turns it into a position. A read() with no exchange
// outstanding (the first, or after a failed write) sends the last commands
// again so that there is an answer to read.
//
// Homing: the device is opened in homing mode with its LED red; the user
// moves the grip all the way out and back in, the firmware flags each motor
// homed as its arm passes the index mark, and from then on the LED is
// green, ForceDeviceState::homed is true and forces are written. Before
// that every packet carries zero torque, whatever write() is asked.
//
// Errors: LIBUSB_ERROR_NO_DEVICE (the cable pulled) -> ForceIo::kRemoved,
// for good; another failed transfer, no answer within the read budget, a
// malformed answer or a pose the kinematics cannot solve -> kFault for that
// tick (counted in counters()).
//
// Units: mm in the device frame (falcon_kinematics.h), N.

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "falcon_firmware.h"
#include "falcon_kinematics.h"
#include "falcon_packet.h"
#include "ftdi_transport.h"
#include "sculpt/base/result.h"
#include "sculpt/hal/force/force_device.h"

namespace sculpt::hal::falcon {

struct FalconOpenOptions {
  /// The firmware image; empty = only a Falcon whose firmware already runs
  /// can be opened.
  std::vector<uint8_t> firmware;
  FirmwareOptions firmware_options;
  /// Zero-force packets sent to learn whether the firmware runs.
  int probe_writes = 10;
  int probe_reads_per_write = 4;
  int probe_read_timeout_ms = 10;
  /// Bulk reads a read() may make for one answer, each up to read_timeout_ms
  /// (the FT232 answers every 1 ms latency period, so 4 reads bound the wait
  /// near one tick).
  int reads_per_exchange = 4;
  int read_timeout_ms = 1;
  int write_timeout_ms = 5;
};

/// Malformed or missing input, for a panel or a test.
struct FalconDeviceCounters {
  FalconPacketCounters packets;
  int64_t exchanges = 0;        ///< read()s that returned kOk
  int64_t missing_answers = 0;  ///< read()s with no whole answer in the budget
  int64_t kinematics_failures = 0;
  int64_t transfer_errors = 0;
};

class FalconDevice final : public ForceDevice {
 public:
  /// Sets up the FTDI chip, loads the firmware when it is not running (with
  /// the retries of options.firmware_options), and enters homing mode.
  /// `info` describes the device for info().
  static Result<std::unique_ptr<FalconDevice>> open(std::unique_ptr<FtdiTransport> transport,
                                                    DeviceInfo info,
                                                    const FalconOpenOptions& options = {});

  const DeviceInfo& info() const override { return info_; }
  const ForceLimits& limits() const override;
  ForceIo read(ForceDeviceState& out) override;
  ForceIo write(glm::vec3 force_n) override;
  void zero() noexcept override;

  const FalconDeviceCounters& counters() const { return counters_; }
  /// The packet the next exchange sends.
  const FalconOutput& output() const { return output_; }
  /// The last decoded answer.
  const FalconInput& input() const { return reader_.newest(); }
  /// Whether open() had to load the firmware.
  bool loaded_firmware() const { return loaded_firmware_; }

 private:
  FalconDevice(std::unique_ptr<FtdiTransport> transport, DeviceInfo info,
               const FalconOpenOptions& options);
  // Sends output_; maps the transfer's status (kRemoved sticks).
  ForceIo send();
  ForceIo usb_failure(UsbStatus status);

  std::unique_ptr<FtdiTransport> transport_;
  DeviceInfo info_;
  FalconOpenOptions options_;
  FtdiReader ftdi_;
  FalconPacketReader reader_;
  FalconOutput output_;
  FalconDeviceCounters counters_;
  FalconMotorLimits motor_limits_;
  glm::dvec3 position_mm_{0.0};
  bool position_valid_ = false;
  bool homed_ = false;
  bool outstanding_ = false;
  bool removed_ = false;
  bool loaded_firmware_ = false;
};

}  // namespace sculpt::hal::falcon
