// FalconDevice: the exchange each tick, homing, and what a failure means.

#include "falcon_device.h"

#include <cassert>
#include <cmath>
#include <utility>

namespace sculpt::hal::falcon {
namespace {

constexpr uint16_t kFalconVendor = 0x0403;
constexpr uint16_t kFalconProduct = 0xcb48;

const ForceLimits& falcon_limits() {
  const ForceLimits* l = find_force_limits(kFalconVendor, kFalconProduct);
  assert(l != nullptr && "the force limits table lost the Falcon");
  return *l;
}

}  // namespace

FalconDevice::FalconDevice(std::unique_ptr<FtdiTransport> transport, DeviceInfo info,
                           const FalconOpenOptions& options)
    : transport_(std::move(transport)),
      info_(std::move(info)),
      options_(options),
      ftdi_(*transport_) {
  motor_limits_.max_force_n = falcon_limits().max_force_n;
  // Red until homed, as libnifalcon's FalconCLIBase::calibrateDevice shows it.
  output_.homing = true;
  output_.leds = kFalconLedRed;
}

Result<std::unique_ptr<FalconDevice>> FalconDevice::open(std::unique_ptr<FtdiTransport> transport,
                                                         DeviceInfo info,
                                                         const FalconOpenOptions& options) {
  assert(transport != nullptr);
  const std::string name = info.id().empty() ? std::string("falcon") : info.id();
  auto usb_error = [&](const char* what, UsbStatus s) {
    return Error(name + ": " + what + ": " + usb_status_name(s));
  };
  // A previous program may have left the chip in a bit-bang mode; mode 0 is
  // the plain UART the firmware talks through. Then the firmware's own line
  // settings, so a firmware that already runs answers the probe.
  if (const UsbStatus s = ftdi_set_bit_mode(*transport, 0x00, 0x00); s != UsbStatus::kOk)
    return usb_error("resetting the bit mode", s);
  if (const UsbStatus s = falcon_enter_run_mode(*transport); s != UsbStatus::kOk)
    return usb_error("setting up the serial line", s);

  FirmwareProbe probe =
      probe_falcon_firmware(*transport, options.probe_writes, options.probe_reads_per_write,
                            options.probe_read_timeout_ms);
  if (probe.status != UsbStatus::kOk) return usb_error("asking for the firmware", probe.status);
  bool loaded = false;
  if (!probe.running) {
    if (options.firmware.empty()) {
      return Error(name +
                   ": the Falcon's firmware is not loaded (it is lost at every power-up); give the "
                   "Novint firmware file with --falcon-firmware FILE");
    }
    if (Status s = load_falcon_firmware(*transport, options.firmware, options.firmware_options);
        !s.ok())
      return s.error().in(name);
    loaded = true;
    probe = probe_falcon_firmware(*transport, options.probe_writes, options.probe_reads_per_write,
                                  options.probe_read_timeout_ms);
    if (probe.status != UsbStatus::kOk) return usb_error("after the firmware upload", probe.status);
    if (!probe.running) {
      return Error(name +
                   ": the firmware was uploaded but the Falcon does not answer its packets; "
                   "is the file the Novint SDK firmware?");
    }
  }
  std::unique_ptr<FalconDevice> device(
      new FalconDevice(std::move(transport), std::move(info), options));
  device->loaded_firmware_ = loaded;
  return device;
}

const ForceLimits& FalconDevice::limits() const {
  return falcon_limits();
}

ForceIo FalconDevice::usb_failure(UsbStatus status) {
  if (status == UsbStatus::kNoDevice) {
    removed_ = true;
    return ForceIo::kRemoved;
  }
  ++counters_.transfer_errors;
  return ForceIo::kFault;
}

ForceIo FalconDevice::send() {
  const FalconPacket packet = encode_falcon_output(output_);
  const UsbTransfer t = transport_->bulk_write(packet, options_.write_timeout_ms);
  if (t.status != UsbStatus::kOk || t.bytes != packet.size()) {
    outstanding_ = false;
    return usb_failure(t.status == UsbStatus::kOk ? UsbStatus::kError : t.status);
  }
  outstanding_ = true;
  return ForceIo::kOk;
}

ForceIo FalconDevice::read(ForceDeviceState& out) {
  if (removed_) return ForceIo::kRemoved;
  if (!outstanding_) {
    if (const ForceIo s = send(); s != ForceIo::kOk) return s;
  }
  outstanding_ = false;
  int found = 0;
  for (int i = 0; i < options_.reads_per_exchange && found == 0; ++i) {
    const UsbStatus s = ftdi_.read_once(options_.read_timeout_ms);
    if (s == UsbStatus::kNoDevice || s == UsbStatus::kError) {
      ftdi_.clear();
      counters_.packets = reader_.counters();
      return usb_failure(s);
    }
    found = reader_.feed(ftdi_.pending());
    ftdi_.clear();
  }
  if (found == 0) {
    ++counters_.missing_answers;
    // An answer cut short: counted, and the partial bytes are dropped so the
    // next exchange starts in step.
    if (reader_.partial() > 0) {
      ++reader_.counters().short_reads;
      reader_.clear();
    }
    counters_.packets = reader_.counters();
    return ForceIo::kFault;
  }
  counters_.packets = reader_.counters();
  const FalconInput& in = reader_.newest();
  if (in.all_homed() && !homed_) {
    homed_ = true;
    output_.leds = kFalconLedGreen;
  }
  out.buttons = in.buttons;
  out.homed = homed_;
  const glm::dvec3 counts{in.encoder[0], in.encoder[1], in.encoder[2]};
  const auto p = falcon_position_mm(falcon_angles_from_counts(counts),
                                    position_valid_ ? position_mm_ : glm::dvec3(0.0));
  if (!p) {
    // Encoders no pose has: before homing they count from wherever the arms
    // stood at power-up, so this is expected then.
    ++counters_.kinematics_failures;
    position_valid_ = false;
    out.position_mm = glm::vec3(position_mm_);
    return homed_ ? ForceIo::kFault : ForceIo::kOk;
  }
  position_mm_ = *p;
  position_valid_ = true;
  out.position_mm = glm::vec3(position_mm_);
  ++counters_.exchanges;
  return ForceIo::kOk;
}

ForceIo FalconDevice::write(glm::vec3 force_n) {
  if (removed_) return ForceIo::kRemoved;
  const bool finite =
      std::isfinite(force_n.x) && std::isfinite(force_n.y) && std::isfinite(force_n.z);
  if (homed_ && position_valid_ && finite) {
    output_.motor = falcon_motor_commands(position_mm_, glm::dvec3(force_n), motor_limits_);
  } else {
    output_.motor = {0, 0, 0};
  }
  const ForceIo s = send();
  if (s != ForceIo::kOk) return s;
  return finite ? ForceIo::kOk : ForceIo::kFault;
}

void FalconDevice::zero() noexcept {
  output_.motor = {0, 0, 0};
  if (removed_) return;
  try {
    (void)send();
  } catch (...) {
    // Best effort: a transport that throws must not take the caller down.
  }
}

}  // namespace sculpt::hal::falcon
