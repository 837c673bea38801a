// The FTDI requests and the status-byte stripping shared by the real and the
// fake transport.

#include "ftdi_transport.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>

namespace sculpt::hal::falcon {

const char* usb_status_name(UsbStatus status) {
  switch (status) {
    case UsbStatus::kOk:
      return "ok";
    case UsbStatus::kTimeout:
      return "timed out";
    case UsbStatus::kNoDevice:
      return "device gone";
    case UsbStatus::kError:
      return "transfer failed";
  }
  return "?";
}

void strip_ftdi_status(std::span<const uint8_t> raw, std::vector<uint8_t>& out) {
  // The FT232 puts its modem status (byte 0) and line status (byte 1) at the
  // head of every USB packet it sends, data or not (libnifalcon
  // src/comm/FalconCommLibUSB.cpp skips "output+2"; FTDI AN232B-04). A
  // transfer into a buffer over 64 bytes may hold several packets, each
  // with its own pair.
  for (size_t at = 0; at < raw.size(); at += kFtdiPacketBytes) {
    const size_t end = std::min(raw.size(), at + kFtdiPacketBytes);
    if (end - at > kFtdiStatusBytes) out.insert(out.end(), raw.begin() + at + 2, raw.begin() + end);
  }
}

Result<FtdiBaudDivisor> ftdi_baud_divisor(uint32_t baud) {
  // FTDI AN232B-05 ("Configuring FT232R, FT2232 and FT232B Baud Rates"): the
  // chip divides a 3 MHz clock (48 MHz / 16) by n + k/8, with n a 14-bit
  // integer and k/8 one of eight fractions; n + k/8 may not lie between 1
  // and 2 except for the two special divisors 1 (3 Mbaud, encoded 0) and
  // 1.5 (2 Mbaud, encoded 1). The fraction travels as a 3-bit code, the
  // low two bits in wValue bits 14-15 and the third in wIndex bit 0; the
  // code for k/8 is {0, 3, 2, 4, 1, 5, 6, 7}[k] (libftdi's
  // ftdi_to_clkbits(), seen in its port in github
  // dinoboards/yellow-msx-series-for-rc2014 msx/apps/helloworld.c). So:
  //   eighths = round(24 MHz / baud)    (the divisor in units of 1/8)
  //   value   = (eighths >> 3) | (code[eighths & 7] & 3) << 14
  //   index   =  code[eighths & 7] >> 2
  // Checks: 9600 baud -> 312.5 -> 0x4138, the value libnifalcon's
  // FalconCommLibUSB.cpp sends; divisor 21 -> 0x0015 and divisor 2 -> 0x0002,
  // its firmware-loading and running rates.
  if (baud == 0) return Error("baud rate 0");
  constexpr uint32_t kEighthsClock = 24'000'000;  // 3 MHz in eighths of a divisor
  constexpr uint32_t kMaxEighths = (0x3fffu << 3) | 7u;
  constexpr std::array<uint8_t, 8> kFractionCode = {0, 3, 2, 4, 1, 5, 6, 7};
  uint64_t eighths = (uint64_t{kEighthsClock} + baud / 2) / baud;
  if (eighths > kMaxEighths) {
    return Error("baud rate " + std::to_string(baud) + " is below the FT232's slowest (" +
                 std::to_string(kEighthsClock / kMaxEighths + 1) + ")");
  }
  FtdiBaudDivisor d;
  if (eighths < 16) {
    // Only 1, 1.5 and 2 are allowed below 2: take the nearest.
    eighths = eighths <= 9 ? 8 : eighths <= 13 ? 12 : 16;
  }
  if (eighths == 8) {
    d.value = 0;
  } else if (eighths == 12) {
    d.value = 1;
  } else {
    const uint8_t code = kFractionCode[eighths & 7];
    d.value = static_cast<uint16_t>((eighths >> 3) | ((code & 3u) << 14));
    d.index = static_cast<uint16_t>(code >> 2);
  }
  d.actual_baud = static_cast<uint32_t>(kEighthsClock / eighths);
  const double off = std::abs(static_cast<double>(d.actual_baud) - baud) / baud;
  if (off > 0.05) {
    return Error("baud rate " + std::to_string(baud) + ": the FT232's nearest is " +
                 std::to_string(d.actual_baud) + ", more than 5% off");
  }
  return d;
}

UsbStatus ftdi_reset(FtdiTransport& t, FtdiReset what) {
  return t.control(FtdiRequest::kReset, static_cast<uint16_t>(what), 0);
}

UsbStatus ftdi_set_latency_timer_ms(FtdiTransport& t, uint8_t ms) {
  return t.control(FtdiRequest::kLatencyTimer, ms, 0);
}

UsbStatus ftdi_set_baud(FtdiTransport& t, uint32_t baud) {
  auto d = ftdi_baud_divisor(baud);
  if (!d.ok()) return UsbStatus::kError;
  return t.control(FtdiRequest::kBaudRate, d->value, d->index);
}

UsbStatus ftdi_set_line_8n1(FtdiTransport& t) {
  // wValue: data bits in bits 0-7, parity (0 = none) in 8-10, stop bits
  // (0 = one) in 11-12 (libftdi ftdi_set_line_property; libnifalcon sends 8).
  return t.control(FtdiRequest::kLineProperties, 8, 0);
}

UsbStatus ftdi_set_flow_control_off(FtdiTransport& t) {
  return t.control(FtdiRequest::kFlowControl, 0, 0);
}

UsbStatus ftdi_set_dtr(FtdiTransport& t, bool high) {
  // High byte: which lines to change (DTR = bit 0); low byte: their levels.
  return t.control(FtdiRequest::kModemControl, high ? 0x0101 : 0x0100, 0);
}

UsbStatus ftdi_set_rts(FtdiTransport& t, bool high) {
  return t.control(FtdiRequest::kModemControl, high ? 0x0202 : 0x0200, 0);
}

UsbStatus ftdi_set_bit_mode(FtdiTransport& t, uint8_t mode, uint8_t mask) {
  return t.control(FtdiRequest::kBitMode, static_cast<uint16_t>((mode << 8) | mask), 0);
}

UsbStatus FtdiReader::read_once(int timeout_ms) {
  raw_.resize(kFtdiPacketBytes);
  const UsbTransfer r = transport_.bulk_read(raw_, timeout_ms);
  const size_t got = std::min(r.bytes, raw_.size());
  strip_ftdi_status(std::span<const uint8_t>(raw_.data(), got), pending_);
  if (r.status == UsbStatus::kTimeout && got > 0) return UsbStatus::kOk;
  return r.status;
}

UsbStatus FtdiReader::read_at_least(size_t n, int max_reads, int timeout_ms) {
  for (int i = 0; i < max_reads && pending_.size() < n; ++i) {
    const UsbStatus s = read_once(timeout_ms);
    if (s == UsbStatus::kNoDevice || s == UsbStatus::kError) return s;
  }
  return pending_.size() >= n ? UsbStatus::kOk : UsbStatus::kTimeout;
}

void FtdiReader::consume(size_t n) {
  pending_.erase(pending_.begin(),
                 pending_.begin() + static_cast<ptrdiff_t>(std::min(n, pending_.size())));
}

}  // namespace sculpt::hal::falcon
