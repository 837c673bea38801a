// The firmware upload's steps. The byte sequences and the order of the FTDI
// requests are libnifalcon's (src/comm/FalconCommLibUSB.cpp setFirmwareMode
// and setNormalMode, src/core/FalconFirmware.cpp loadFirmware); the code is
// ours. Where libnifalcon's comm layers disagree, the comment says which we
// follow and why.

#include "falcon_firmware.h"

#include <algorithm>
#include <array>
#include <cstdio>
#include <fstream>

#include "falcon_packet.h"
#include "sculpt/base/input_file.h"

namespace sculpt::hal::falcon {
namespace {

// The bootloader's greeting: we send LF 'C' CR and it answers LF 'D' ',' CR.
constexpr std::array<uint8_t, 3> kHandshakeSend = {0x0a, 0x43, 0x0d};
constexpr std::array<uint8_t, 4> kHandshakeAnswer = {0x0a, 0x44, 0x2c, 0x0d};
constexpr uint8_t kSyncByte = 0x41;  // 'A', echoed
// FalconCommFTD2XX.cpp's comment expects 0x13 (XOFF) before the echo on some
// hosts; it is skipped when present.
constexpr uint8_t kXoff = 0x13;

constexpr uint32_t kHandshakeBaud = 9600;
// libnifalcon's libusb layer sends divisor 0x0015 (3 MHz / 21 = 142857
// baud); its libftdi and FTD2XX layers ask for 140000, which the FT232B
// rules turn into 21 3/8. Both work, 2 % apart (a UART's tolerance); we
// send the libusb layer's value, the path proven on Linux with libusb.
constexpr uint32_t kBootloaderBaud = 142857;
// setNormalMode: divisor 2, 1.5 Mbaud (the libftdi and FTD2XX layers ask
// for 1456312, which rounds to the same divisor).
constexpr uint32_t kRunBaud = 1'500'000;
// "Make sure our latency timer is at 16ms, otherwise firmware checks tend
// to always fail" (FalconCommLibUSB.cpp); 1 ms in run mode, or each 16-byte
// answer would wait for the timer (the packet is shorter than a USB packet).
constexpr uint8_t kBootLatencyMs = 16;
constexpr uint8_t kRunLatencyMs = 1;

std::string hex(std::span<const uint8_t> bytes, size_t max = 8) {
  std::string s;
  char b[4];
  for (size_t i = 0; i < bytes.size() && i < max; ++i) {
    std::snprintf(b, sizeof b, "%s%02x", i ? " " : "", bytes[i]);
    s += b;
  }
  if (bytes.size() > max) s += " ...";
  return s.empty() ? "nothing" : s;
}

}  // namespace

const char* firmware_step_name(FirmwareStep step) {
  switch (step) {
    case FirmwareStep::kSetUp:
      return "set-up";
    case FirmwareStep::kHandshake:
      return "handshake";
    case FirmwareStep::kBootBaud:
      return "bootloader baud rate";
    case FirmwareStep::kSync:
      return "sync";
    case FirmwareStep::kUpload:
      return "upload";
    case FirmwareStep::kRunMode:
      return "run mode";
    case FirmwareStep::kDone:
      return "done";
    case FirmwareStep::kFailed:
      return "failed";
  }
  return "?";
}

FirmwareUpload::FirmwareUpload(FtdiTransport& transport, std::span<const uint8_t> image,
                               const FirmwareOptions& options)
    : transport_(transport), image_(image), options_(options), reader_(transport) {
  if (options_.chunk_bytes == 0 || options_.chunk_bytes > kFtdiPacketBytes - kFtdiStatusBytes)
    options_.chunk_bytes = kFtdiPacketBytes - kFtdiStatusBytes;
}

FirmwareStep FirmwareUpload::fail(std::string why) {
  error_ = std::string(firmware_step_name(step_)) + ": " + why;
  step_ = FirmwareStep::kFailed;
  return step_;
}

FirmwareStep FirmwareUpload::fail_usb(const char* what, UsbStatus status) {
  device_gone_ = status == UsbStatus::kNoDevice;
  return fail(std::string(what) + ": " + usb_status_name(status));
}

FirmwareStep FirmwareUpload::advance() {
  switch (step_) {
    case FirmwareStep::kSetUp:
      return set_up();
    case FirmwareStep::kHandshake:
      return handshake();
    case FirmwareStep::kBootBaud:
      return boot_baud();
    case FirmwareStep::kSync:
      return sync();
    case FirmwareStep::kUpload:
      return upload_chunk();
    case FirmwareStep::kRunMode:
      return run_mode();
    case FirmwareStep::kDone:
    case FirmwareStep::kFailed:
      break;
  }
  return step_;
}

FirmwareStep FirmwareUpload::run() {
  while (step_ != FirmwareStep::kDone && step_ != FirmwareStep::kFailed)
    advance();
  return step_;
}

FirmwareStep FirmwareUpload::set_up() {
  if (image_.empty()) return fail("the firmware image is empty");
  struct Request {
    const char* what;
    UsbStatus (*send)(FtdiTransport&);
  };
  // DTR low then high resets the microcontroller into its bootloader.
  static constexpr Request kRequests[] = {
      {"purge rx", [](FtdiTransport& t) { return ftdi_reset(t, FtdiReset::kPurgeRx); }},
      {"purge tx", [](FtdiTransport& t) { return ftdi_reset(t, FtdiReset::kPurgeTx); }},
      {"latency timer",
       [](FtdiTransport& t) { return ftdi_set_latency_timer_ms(t, kBootLatencyMs); }},
      {"baud rate", [](FtdiTransport& t) { return ftdi_set_baud(t, kHandshakeBaud); }},
      {"line 8N1", [](FtdiTransport& t) { return ftdi_set_line_8n1(t); }},
      {"flow control", [](FtdiTransport& t) { return ftdi_set_flow_control_off(t); }},
      {"RTS low", [](FtdiTransport& t) { return ftdi_set_rts(t, false); }},
      {"DTR low", [](FtdiTransport& t) { return ftdi_set_dtr(t, false); }},
      {"DTR high", [](FtdiTransport& t) { return ftdi_set_dtr(t, true); }},
  };
  for (const Request& r : kRequests) {
    if (const UsbStatus s = r.send(transport_); s != UsbStatus::kOk) return fail_usb(r.what, s);
  }
  reader_.clear();
  step_ = FirmwareStep::kHandshake;
  return step_;
}

FirmwareStep FirmwareUpload::handshake() {
  std::vector<uint8_t> last;
  for (int attempt = 0; attempt < options_.handshake_tries; ++attempt) {
    reader_.clear();
    const UsbTransfer w = transport_.bulk_write(kHandshakeSend, options_.write_timeout_ms);
    if (w.status != UsbStatus::kOk) return fail_usb("writing 0a 43 0d", w.status);
    // A leading 0x00 comes on some hosts (libnifalcon's "Apple case").
    const UsbStatus r = reader_.read_at_least(kHandshakeAnswer.size(), options_.reads_per_answer,
                                              options_.read_timeout_ms);
    if (r == UsbStatus::kNoDevice || r == UsbStatus::kError)
      return fail_usb("reading the answer", r);
    std::vector<uint8_t>& got = reader_.pending();
    while (got.size() > kHandshakeAnswer.size() && got.front() == 0x00)
      got.erase(got.begin());
    if (got.size() >= kHandshakeAnswer.size() &&
        std::equal(kHandshakeAnswer.begin(), kHandshakeAnswer.end(), got.begin())) {
      reader_.clear();
      step_ = FirmwareStep::kBootBaud;
      return step_;
    }
    last = got;
  }
  return fail("no answer 0a 44 2c 0d to 0a 43 0d in " + std::to_string(options_.handshake_tries) +
              " tries (last: " + hex(last) + ")");
}

FirmwareStep FirmwareUpload::boot_baud() {
  if (const UsbStatus s = ftdi_set_dtr(transport_, false); s != UsbStatus::kOk)
    return fail_usb("DTR low", s);
  if (const UsbStatus s = ftdi_set_baud(transport_, kBootloaderBaud); s != UsbStatus::kOk)
    return fail_usb("baud rate", s);
  step_ = FirmwareStep::kSync;
  return step_;
}

FirmwareStep FirmwareUpload::sync() {
  reader_.clear();
  const uint8_t a = kSyncByte;
  const UsbTransfer w =
      transport_.bulk_write(std::span<const uint8_t>(&a, 1), options_.write_timeout_ms);
  if (w.status != UsbStatus::kOk) return fail_usb("writing 'A'", w.status);
  UsbStatus r = reader_.read_at_least(1, options_.reads_per_answer, options_.read_timeout_ms);
  std::vector<uint8_t>& got = reader_.pending();
  if (!got.empty() && got.front() == kXoff) {
    got.erase(got.begin());
    if (got.empty())
      r = reader_.read_at_least(1, options_.reads_per_answer, options_.read_timeout_ms);
  }
  if (r == UsbStatus::kNoDevice || r == UsbStatus::kError)
    return fail_usb("reading the echo of 'A'", r);
  if (got.empty() || got.front() != kSyncByte) return fail("'A' (41) echoed as " + hex(got));
  reader_.clear();
  step_ = FirmwareStep::kUpload;
  return step_;
}

FirmwareStep FirmwareUpload::upload_chunk() {
  const size_t n = std::min(options_.chunk_bytes, image_.size() - uploaded_);
  const std::span<const uint8_t> chunk = image_.subspan(uploaded_, n);
  const UsbTransfer w = transport_.bulk_write(chunk, options_.write_timeout_ms);
  if (w.status != UsbStatus::kOk || w.bytes != n) {
    if (w.status != UsbStatus::kOk)
      return fail_usb(("writing bytes " + std::to_string(uploaded_)).c_str(), w.status);
    return fail("wrote " + std::to_string(w.bytes) + " of " + std::to_string(n) + " bytes at " +
                std::to_string(uploaded_));
  }
  const UsbStatus r = reader_.read_at_least(n, options_.reads_per_answer, options_.read_timeout_ms);
  if (r == UsbStatus::kNoDevice || r == UsbStatus::kError) return fail_usb("reading the echo", r);
  const std::vector<uint8_t>& got = reader_.pending();
  if (got.size() < n) {
    return fail("echo of bytes " + std::to_string(uploaded_) + ".." +
                std::to_string(uploaded_ + n - 1) + " stopped after " + std::to_string(got.size()));
  }
  if (options_.check_echo) {
    const auto mismatch = std::mismatch(chunk.begin(), chunk.end(), got.begin());
    if (mismatch.first != chunk.end()) {
      const size_t at = uploaded_ + static_cast<size_t>(mismatch.first - chunk.begin());
      char b[96];
      std::snprintf(b, sizeof b, "byte %zu echoed as %02x, sent %02x", at, *mismatch.second,
                    *mismatch.first);
      return fail(b);
    }
  }
  reader_.consume(n);
  uploaded_ += n;
  if (uploaded_ == image_.size()) step_ = FirmwareStep::kRunMode;
  return step_;
}

FirmwareStep FirmwareUpload::run_mode() {
  if (const UsbStatus s = falcon_enter_run_mode(transport_); s != UsbStatus::kOk)
    return fail_usb("switching to 1.5 Mbaud", s);
  step_ = FirmwareStep::kDone;
  return step_;
}

UsbStatus falcon_enter_run_mode(FtdiTransport& t) {
  for (const UsbStatus s :
       {ftdi_set_latency_timer_ms(t, kRunLatencyMs), ftdi_set_baud(t, kRunBaud),
        ftdi_reset(t, FtdiReset::kPurgeRx), ftdi_reset(t, FtdiReset::kPurgeTx)}) {
    if (s != UsbStatus::kOk) return s;
  }
  return UsbStatus::kOk;
}

Status load_falcon_firmware(FtdiTransport& transport, std::span<const uint8_t> image,
                            const FirmwareOptions& options, FirmwareReport* report) {
  FirmwareReport local;
  FirmwareReport& rep = report ? *report : local;
  rep = {};
  const int attempts = std::max(1, options.attempts);
  std::string last;
  for (int i = 0; i < attempts; ++i) {
    FirmwareUpload upload(transport, image, options);
    ++rep.attempts;
    if (upload.run() == FirmwareStep::kDone) return {};
    last = upload.error();
    rep.failures.push_back(last);
    if (upload.device_gone()) return Error("Falcon firmware: the device went away (" + last + ")");
  }
  return Error("Falcon firmware: gave up after " + std::to_string(attempts) +
               (attempts == 1 ? " attempt" : " attempts") + "; the last failed at " + last);
}

FirmwareProbe probe_falcon_firmware(FtdiTransport& transport, int writes, int reads_per_write,
                                    int read_timeout_ms) {
  FirmwareProbe probe;
  const FalconPacket zero = encode_falcon_output({});
  FtdiReader reader(transport);
  FalconPacketReader packets;
  for (int w = 0; w < writes; ++w) {
    const UsbTransfer t = transport.bulk_write(zero, 100);
    if (t.status == UsbStatus::kNoDevice || t.status == UsbStatus::kError) {
      probe.status = t.status;
      return probe;
    }
    for (int r = 0; r < reads_per_write; ++r) {
      const UsbStatus s = reader.read_once(read_timeout_ms);
      if (s == UsbStatus::kNoDevice || s == UsbStatus::kError) {
        probe.status = s;
        return probe;
      }
      packets.feed(reader.pending());
      reader.clear();
      if (packets.counters().packets > 0) {
        probe.running = true;
        return probe;
      }
    }
  }
  return probe;
}

Result<std::vector<uint8_t>> read_falcon_firmware_file(const std::string& path) {
  constexpr std::streamoff kMaxBytes = 1 << 20;
  if (const Status s = check_input_file(path); !s) return s.error();
  std::ifstream in(path, std::ios::binary);
  if (!in) return Error(path + ": cannot open the Falcon firmware file");
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  if (size <= 0) return Error(path + ": the Falcon firmware file is empty");
  if (size > kMaxBytes) {
    return Error(path + ": " + std::to_string(size) +
                 " bytes is too large for Falcon firmware (at most 1 MiB); is it the right file?");
  }
  in.seekg(0);
  std::vector<uint8_t> bytes(static_cast<size_t>(size));
  if (!in.read(reinterpret_cast<char*>(bytes.data()), size)) return Error(path + ": read failed");
  return bytes;
}

}  // namespace sculpt::hal::falcon
