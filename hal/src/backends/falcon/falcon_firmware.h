#pragma once
// Loading the Novint SDK firmware into a Falcon, which forgets it at every
// power-up: a bootloader on the Falcon's microcontroller takes it over the
// FTDI serial line. The user supplies the file (station option
// --falcon-firmware FILE): it is Novint's, not ours to ship, and nothing is
// downloaded.
//
// One attempt is a state machine (FirmwareUpload) driven by the transport:
//
//   kSetUp      purge, latency timer 16 ms, 9600 baud 8N1, no flow control,
//               RTS low, DTR low then high (this resets into the bootloader)
//   kHandshake  send 0a 43 0d, expect 0a 44 2c 0d (up to 100 tries)
//   kBootBaud   DTR low, 3 MHz / 21 (142857 baud)
//   kSync       send 'A', expect 'A' back
//   kUpload     the image in chunks of 62 bytes, each echoed by the device
//   kRunMode    latency timer 1 ms, 1.5 Mbaud, purge: the firmware's rate
//
// then kDone, or kFailed with an Error naming the step. Uploads fail now and
// then (libnifalcon's tools retry up to 10 times), so load_falcon_firmware()
// runs up to `attempts` of them.
//
// Source of every byte and rate: libnifalcon src/comm/FalconCommLibUSB.cpp
// (setFirmwareMode, setNormalMode) and src/core/FalconFirmware.cpp
// (loadFirmware, isFirmwareLoaded).

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "ftdi_transport.h"
#include "sculpt/base/result.h"

namespace sculpt::hal::falcon {

enum class FirmwareStep : uint8_t {
  kSetUp,
  kHandshake,
  kBootBaud,
  kSync,
  kUpload,
  kRunMode,
  kDone,
  kFailed
};
const char* firmware_step_name(FirmwareStep step);

struct FirmwareOptions {
  /// Whole uploads tried before giving up.
  int attempts = 10;
  /// Handshake messages sent per attempt before the attempt fails.
  int handshake_tries = 100;
  /// Bulk reads per expected answer; each returns after at most read_timeout_ms
  /// (an idle FT232 answers every latency period with its two status bytes).
  int reads_per_answer = 8;
  int read_timeout_ms = 100;
  int write_timeout_ms = 1000;
  /// Bytes per upload chunk: the echo must fit one 64-byte IN packet with
  /// its two status bytes.
  size_t chunk_bytes = 62;
  /// Compare each echoed byte with the one sent (libnifalcon's findfalcons
  /// skips this; a mismatch here fails the attempt, and it is retried).
  bool check_echo = true;
};

/// One upload attempt, a step at a time.
class FirmwareUpload {
 public:
  /// `image` must outlive the upload.
  FirmwareUpload(FtdiTransport& transport, std::span<const uint8_t> image,
                 const FirmwareOptions& options = {});
  FirmwareStep step() const { return step_; }
  /// Runs the current step; returns the step now current.
  FirmwareStep advance();
  /// Runs to kDone or kFailed.
  FirmwareStep run();
  /// Why it failed ("handshake: ..."); empty unless kFailed.
  const std::string& error() const { return error_; }
  /// True when the failure was the device going away (no retry helps).
  bool device_gone() const { return device_gone_; }
  size_t uploaded_bytes() const { return uploaded_; }

 private:
  FirmwareStep fail(std::string why);
  FirmwareStep fail_usb(const char* what, UsbStatus status);
  FirmwareStep set_up();
  FirmwareStep handshake();
  FirmwareStep boot_baud();
  FirmwareStep sync();
  FirmwareStep upload_chunk();
  FirmwareStep run_mode();

  FtdiTransport& transport_;
  std::span<const uint8_t> image_;
  FirmwareOptions options_;
  FtdiReader reader_;
  FirmwareStep step_ = FirmwareStep::kSetUp;
  std::string error_;
  bool device_gone_ = false;
  size_t uploaded_ = 0;
};

/// What load_falcon_firmware did.
struct FirmwareReport {
  int attempts = 0;
  /// The error of each failed attempt, in order.
  std::vector<std::string> failures;
};

/// Uploads `image` with retries. The Error names the last failing step
/// ("Falcon firmware: gave up after 10 attempts; the last failed at upload:
/// ..."), or says the device went away.
Status load_falcon_firmware(FtdiTransport& transport, std::span<const uint8_t> image,
                            const FirmwareOptions& options = {}, FirmwareReport* report = nullptr);

/// The firmware's serial settings (kRunMode alone): for a Falcon whose
/// firmware is already running.
UsbStatus falcon_enter_run_mode(FtdiTransport& transport);

/// Whether the Novint SDK firmware already runs (it survives until the
/// Falcon loses power): in run mode, a zero-force packet is sent up to
/// `writes` times, each followed by up to `reads_per_write` reads, and any
/// well-framed answer means yes (libnifalcon FalconFirmware::isFirmwareLoaded
/// does the same with 10 x 100 loops). `status` is kNoDevice or kError when
/// the transport failed, and then `running` means nothing.
struct FirmwareProbe {
  bool running = false;
  UsbStatus status = UsbStatus::kOk;
};
FirmwareProbe probe_falcon_firmware(FtdiTransport& transport, int writes = 10,
                                    int reads_per_write = 4, int read_timeout_ms = 10);

/// Reads a firmware file the user names; an Error naming the file when it
/// cannot be read, is empty or is larger than any Falcon firmware (1 MiB).
Result<std::vector<uint8_t>> read_falcon_firmware_file(const std::string& path);

}  // namespace sculpt::hal::falcon
