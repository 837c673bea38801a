#pragma once
// A byte-level fake of the Falcon's USB edge for the tests: it records every
// control request and bulk write, and answers bulk reads from a script of
// raw IN transfers (FTDI status bytes included, so short, status-only and
// garbage reads can be scripted). A responder, when set, is called on each
// bulk write and may script the device's answer to it.

#include <cstdint>
#include <deque>
#include <functional>
#include <span>
#include <vector>

#include "backends/falcon/ftdi_transport.h"

namespace sculpt::hal::falcon::testing {

struct ControlRecord {
  FtdiRequest request;
  uint16_t value;
  uint16_t index;
  bool operator==(const ControlRecord&) const = default;
};

struct ScriptedRead {
  UsbStatus status = UsbStatus::kOk;
  std::vector<uint8_t> raw;  // as the chip sends it: status bytes first
};

class FakeFtdiTransport final : public FtdiTransport {
 public:
  /// The status bytes an idle FT232 puts at the head of its packets.
  static constexpr uint8_t kModemStatus = 0x31;
  static constexpr uint8_t kLineStatus = 0x60;

  UsbStatus control(FtdiRequest request, uint16_t value, uint16_t index) override {
    controls.push_back({request, value, index});
    return gone ? UsbStatus::kNoDevice : control_status;
  }
  UsbTransfer bulk_write(std::span<const uint8_t> bytes, int) override {
    if (gone) return {UsbStatus::kNoDevice, 0};
    if (write_status != UsbStatus::kOk) return {write_status, 0};
    writes.emplace_back(bytes.begin(), bytes.end());
    if (responder) responder(bytes, *this);
    return {UsbStatus::kOk, bytes.size()};
  }
  UsbTransfer bulk_read(std::span<uint8_t> buf, int) override {
    ++reads;
    if (gone) return {UsbStatus::kNoDevice, 0};
    if (script.empty()) {
      // An idle chip: its status bytes and nothing else.
      buf[0] = kModemStatus;
      buf[1] = kLineStatus;
      return {UsbStatus::kOk, 2};
    }
    ScriptedRead r = std::move(script.front());
    script.pop_front();
    const size_t n = std::min(buf.size(), r.raw.size());
    std::copy_n(r.raw.begin(), n, buf.begin());
    return {r.status, n};
  }

  /// Queues `payload` as the device's data, in packets of 62 bytes each
  /// behind the two status bytes, as the chip splits it.
  void answer(std::span<const uint8_t> payload) {
    for (size_t at = 0; at < payload.size(); at += 62) {
      ScriptedRead r;
      r.raw = {kModemStatus, kLineStatus};
      const size_t end = std::min(payload.size(), at + 62);
      r.raw.insert(r.raw.end(), payload.begin() + static_cast<ptrdiff_t>(at),
                   payload.begin() + static_cast<ptrdiff_t>(end));
      script.push_back(std::move(r));
    }
  }
  void answer(std::initializer_list<uint8_t> payload) {
    const std::vector<uint8_t> v(payload);
    answer(std::span<const uint8_t>(v));
  }
  void answer_raw(std::vector<uint8_t> raw, UsbStatus status = UsbStatus::kOk) {
    script.push_back({status, std::move(raw)});
  }

  std::vector<ControlRecord> controls;
  std::vector<std::vector<uint8_t>> writes;
  std::deque<ScriptedRead> script;
  std::function<void(std::span<const uint8_t>, FakeFtdiTransport&)> responder;
  UsbStatus control_status = UsbStatus::kOk;
  UsbStatus write_status = UsbStatus::kOk;
  bool gone = false;  ///< unplugged: every call says kNoDevice
  int reads = 0;
};

}  // namespace sculpt::hal::falcon::testing
