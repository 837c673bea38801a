#pragma once
// The USB edge of the Novint Falcon: an FTDI FT232-family USB-serial chip
// (0403:cb48) on interface 0, bulk OUT 0x02 and bulk IN 0x81, configured by
// vendor control requests. FtdiTransport is the byte-level interface the
// firmware loader (falcon_firmware.h) and the device (falcon_device.h) talk
// through: a libusb implementation (libusb_ftdi_transport.h) drives a real
// Falcon, a scripted fake drives the tests.
//
// bulk_read() returns the IN transfer as the chip sends it: every USB packet
// (up to 64 bytes) begins with two modem/line status bytes, so a read with no
// data still returns 2 bytes. FtdiReader strips them.
//
// Thread safety: none; one thread uses a transport at a time.

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "sculpt/base/result.h"

namespace sculpt::hal::falcon {

/// What a USB transfer came to.
enum class UsbStatus : uint8_t {
  kOk,
  kTimeout,   ///< nothing (or less than asked) within the timeout
  kNoDevice,  ///< the device is gone (LIBUSB_ERROR_NO_DEVICE): unplugged
  kError,     ///< any other failure (pipe stall, I/O error, ...)
};
const char* usb_status_name(UsbStatus status);

struct UsbTransfer {
  UsbStatus status = UsbStatus::kOk;
  /// Bytes moved, also on a timeout (a partial transfer).
  size_t bytes = 0;
};

/// The FT232's vendor requests (bRequest), from libftdi's ftdi.h
/// (SIO_*_REQUEST), as listed in github jonas-schievink/ftdi-protocol README.md.
enum class FtdiRequest : uint8_t {
  kReset = 0x00,
  kModemControl = 0x01,
  kFlowControl = 0x02,
  kBaudRate = 0x03,
  kLineProperties = 0x04,
  kLatencyTimer = 0x09,
  kBitMode = 0x0b,
};

/// wValue of kReset.
enum class FtdiReset : uint16_t { kSio = 0, kPurgeRx = 1, kPurgeTx = 2 };

class FtdiTransport {
 public:
  virtual ~FtdiTransport() = default;
  /// A vendor OUT control request to the device (bmRequestType 0x40, no data).
  virtual UsbStatus control(FtdiRequest request, uint16_t value, uint16_t index) = 0;
  /// Writes `bytes` to bulk OUT 0x02.
  virtual UsbTransfer bulk_write(std::span<const uint8_t> bytes, int timeout_ms) = 0;
  /// Reads from bulk IN 0x81 into `buf` (at least 64 bytes), status bytes included.
  virtual UsbTransfer bulk_read(std::span<uint8_t> buf, int timeout_ms) = 0;
};

/// The USB packet size of the Falcon's bulk IN endpoint (full speed).
inline constexpr size_t kFtdiPacketBytes = 64;
/// The modem and line status bytes that open every IN packet.
inline constexpr size_t kFtdiStatusBytes = 2;

/// Appends the payload of a raw IN transfer to `out`: each 64-byte packet
/// loses its first two bytes; a packet of 2 bytes or fewer carries nothing.
void strip_ftdi_status(std::span<const uint8_t> raw, std::vector<uint8_t>& out);

/// An FT232B/R baud rate setting: wValue and wIndex of the kBaudRate request.
struct FtdiBaudDivisor {
  uint16_t value = 0;
  uint16_t index = 0;
  /// The rate the chip then runs at, baud (rounded down).
  uint32_t actual_baud = 0;
};

/// The divisor nearest to `baud` for an FT232B/R (3 MHz base clock, divisor
/// in eighths); an Error for rates it cannot come within 5 % of.
Result<FtdiBaudDivisor> ftdi_baud_divisor(uint32_t baud);

// The set-up requests, named. Each returns the control request's status.
UsbStatus ftdi_reset(FtdiTransport& t, FtdiReset what);
UsbStatus ftdi_set_latency_timer_ms(FtdiTransport& t, uint8_t ms);
/// Fails with kError (sending nothing) for a rate ftdi_baud_divisor refuses.
UsbStatus ftdi_set_baud(FtdiTransport& t, uint32_t baud);
UsbStatus ftdi_set_line_8n1(FtdiTransport& t);
UsbStatus ftdi_set_flow_control_off(FtdiTransport& t);
UsbStatus ftdi_set_dtr(FtdiTransport& t, bool high);
UsbStatus ftdi_set_rts(FtdiTransport& t, bool high);
/// mode 0x00 = the plain UART (reset any bit-bang mode); mask = pin directions.
UsbStatus ftdi_set_bit_mode(FtdiTransport& t, uint8_t mode, uint8_t mask);

/// Reads a transport's IN data with the status bytes gone. Keeps the bytes
/// of a transfer not yet taken, so a caller asking for 4 bytes does not lose
/// the 5th.
class FtdiReader {
 public:
  explicit FtdiReader(FtdiTransport& transport) : transport_(transport) {}
  /// One bulk read; its payload goes to pending(). kOk even when the packet
  /// held only status bytes; the status of the transfer otherwise.
  UsbStatus read_once(int timeout_ms);
  /// Reads until pending() holds at least n bytes or `max_reads` reads have
  /// passed (each with timeout_ms). kTimeout when short.
  UsbStatus read_at_least(size_t n, int max_reads, int timeout_ms);
  std::vector<uint8_t>& pending() { return pending_; }
  /// Removes the first n pending bytes.
  void consume(size_t n);
  void clear() { pending_.clear(); }

 private:
  FtdiTransport& transport_;
  std::vector<uint8_t> pending_;
  std::vector<uint8_t> raw_;
};

}  // namespace sculpt::hal::falcon
