#pragma once
// A scripted Falcon behind FakeFtdiTransport: a bootloader that answers the
// handshake and echoes the upload (with failures on chosen attempts), and,
// once loaded (or from the start), a firmware that answers each 16-byte
// packet with encoders, buttons and homed flags the test sets. The packets
// are built here by hand, not with the codec under test.

#include <array>
#include <cstdint>
#include <optional>
#include <set>
#include <span>
#include <vector>

#include "fake_ftdi_transport.h"

namespace sculpt::hal::falcon::testing {

/// A device packet, built byte by byte.
inline std::vector<uint8_t> device_packet(std::array<int16_t, 3> encoders, uint8_t buttons,
                                          uint8_t homed) {
  std::vector<uint8_t> p = {'<'};
  for (int16_t e : encoders) {
    const auto v = static_cast<uint16_t>(e);
    for (int n = 0; n < 4; ++n)
      p.push_back(static_cast<uint8_t>('A' + ((v >> (4 * n)) & 0xf)));
  }
  p.push_back(static_cast<uint8_t>('A' + (buttons & 0xf) + ((homed & 7) << 4)));
  p.push_back('A');
  p.push_back('>');
  return p;
}

/// The motor commands in a host packet, or nullopt when it is not one.
inline std::optional<std::array<int16_t, 3>> host_motors(std::span<const uint8_t> p) {
  if (p.size() != 16 || p[0] != '<' || p[15] != '>') return std::nullopt;
  std::array<int16_t, 3> m{};
  for (int i = 0; i < 3; ++i) {
    uint16_t v = 0;
    for (int n = 0; n < 4; ++n)
      v = static_cast<uint16_t>(v | ((p[1 + 4 * i + n] - 'A') << (4 * n)));
    m[static_cast<size_t>(i)] = static_cast<int16_t>(v);
  }
  return m;
}

struct FakeFalcon {
  // Bootloader behaviour, by attempt (1-based: the n-th DTR-high reset).
  std::set<int> silent_handshake_attempts;  ///< the handshake gets garbage
  std::set<int> corrupt_echo_attempts;      ///< byte corrupt_at of the upload echoes wrong
  size_t corrupt_at = 70;
  std::set<int> gone_during_upload_attempts;
  // Firmware behaviour.
  bool firmware_running = false;
  std::array<int16_t, 3> encoders{0, 0, 0};
  uint8_t buttons = 0;
  uint8_t homed = 0;
  /// What the firmware received, one entry per host packet.
  std::vector<std::array<int16_t, 3>> motors;
  std::vector<uint8_t> flags;
  std::vector<uint8_t> uploaded;

  int attempt = 0;
  bool booting = false;  // after the switch to the bootloader's baud rate

  void attach(FakeFtdiTransport& fake) {
    fake.responder = [this](std::span<const uint8_t> bytes, FakeFtdiTransport& t) {
      on_write(bytes, t);
    };
  }

  void on_write(std::span<const uint8_t> bytes, FakeFtdiTransport& t) {
    // Follow the set-up requests the host has made since the last write.
    for (; seen_controls_ < t.controls.size(); ++seen_controls_) {
      const ControlRecord& c = t.controls[seen_controls_];
      if (c.request == FtdiRequest::kModemControl && c.value == 0x0101) {
        ++attempt;
        booting = false;
        firmware_running = false;  // DTR resets the microcontroller
        uploaded.clear();
      }
      if (c.request == FtdiRequest::kBaudRate) {
        booting = c.value == 0x0015;
        if (c.value == 0x0002 && !uploaded.empty() && !booting) firmware_running = true;
      }
    }
    if (booting) {
      std::vector<uint8_t> echo(bytes.begin(), bytes.end());
      const bool sync = bytes.size() == 1 && bytes[0] == 'A' && uploaded.empty() && !synced_;
      if (sync) {
        synced_ = true;
      } else {
        for (size_t i = 0; i < echo.size(); ++i) {
          if (corrupt_echo_attempts.count(attempt) && uploaded.size() + i == corrupt_at)
            echo[i] ^= 0x5a;
        }
        uploaded.insert(uploaded.end(), bytes.begin(), bytes.end());
        if (gone_during_upload_attempts.count(attempt)) {
          t.gone = true;
          return;
        }
      }
      t.answer(echo);
      return;
    }
    synced_ = false;
    const std::vector<uint8_t> hello = {0x0a, 0x43, 0x0d};
    if (std::vector<uint8_t>(bytes.begin(), bytes.end()) == hello) {
      if (silent_handshake_attempts.count(attempt)) {
        t.answer({0x0a, 0x45});
      } else {
        t.answer({0x0a, 0x44, 0x2c, 0x0d});
      }
      return;
    }
    if (firmware_running) {
      if (auto m = host_motors(bytes)) {
        motors.push_back(*m);
        flags.push_back(static_cast<uint8_t>(bytes[13] - 'A'));
        t.answer(device_packet(encoders, buttons, homed));
      }
    }
  }

 private:
  size_t seen_controls_ = 0;
  bool synced_ = false;
};

}  // namespace sculpt::hal::falcon::testing
