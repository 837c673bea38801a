#pragma once
// opentrack: a receiver of OpenTrack's "UDP over network" output, one
// tracker per listening port (`opentrack[:PORT]`, default 4242).
//
// Each accepted datagram becomes one kReport RawEvent holding the 48 bytes
// as they arrived, so a session records them and a replay decodes the same
// pose (decode_opentrack_datagram). A kReport with no bytes means "tracking
// lost": no datagram for lost_after_ms after tracking was on.
//
// Network safety: binds to the loopback address unless given another
// listen address; the first sender of a good datagram is locked in and
// datagrams from any other address or port are counted and dropped.
//
// Thread safety: as every Device, read by one thread; counters() from that
// thread only.

#include <cstdint>
#include <memory>
#include <string>

#include "sculpt/hal/types/device.h"

namespace sculpt::hal {

inline constexpr uint16_t kOpenTrackDefaultPort = 4242;

struct OpenTrackOptions {
  uint16_t port = kOpenTrackDefaultPort;     ///< 0: an ephemeral port (tests); see bound_port()
  std::string listen_address = "127.0.0.1";  ///< IPv4 dotted quad; another host needs it set
  int lost_after_ms = 250;                   ///< silence that counts as tracking lost
};

/// What the receiver dropped, and why. Every datagram is counted once.
struct OpenTrackCounters {
  int64_t datagrams = 0;   ///< received from the socket
  int64_t accepted = 0;    ///< delivered as a report
  int64_t superseded = 0;  ///< good, but a newer one arrived in the same drain
  int64_t short_datagrams = 0;
  int64_t long_datagrams = 0;
  int64_t not_finite = 0;      ///< NaN or infinity inside
  int64_t foreign_sender = 0;  ///< not from the locked-in sender
  int64_t tracking_lost = 0;   ///< "lost" reports delivered
};

class OpenTrackDevice final : public Device {
 public:
  ~OpenTrackDevice() override;
  /// Binds the socket. Errors name the address and port ("127.0.0.1:4242:
  /// Address already in use").
  static Result<std::unique_ptr<OpenTrackDevice>> open(const OpenTrackOptions& options);

  const DeviceInfo& info() const override { return info_; }
  /// Waits up to timeout_ms, then drains the socket and delivers the newest
  /// good datagram (or a "lost" report). Never kRemoved: a tracker that
  /// falls silent may come back.
  ReadResult read(RawEvent& out, int timeout_ms) override;

  uint16_t bound_port() const { return bound_port_; }
  const OpenTrackCounters& counters() const { return counters_; }
  /// "127.0.0.1:53122" once a sender is locked in, else empty.
  std::string locked_sender() const;

 private:
  OpenTrackDevice(int fd, uint16_t port, const OpenTrackOptions& options);
  /// Reads every queued datagram; true when `newest` holds a good one.
  bool drain(RawEvent& newest, int64_t now_ns);

  int fd_ = -1;
  uint16_t bound_port_ = 0;
  int64_t lost_after_ns_ = 0;
  DeviceInfo info_;
  OpenTrackCounters counters_;
  bool sender_locked_ = false;
  uint32_t sender_ip_ = 0;    // network order
  uint16_t sender_port_ = 0;  // network order
  bool tracking_ = false;     // a good datagram arrived and no "lost" since
  int64_t last_good_ns_ = 0;
};

/// A backend with one device, the listener of `options`. enumerate() lists
/// it without binding (listeners open only when asked for).
std::unique_ptr<Backend> make_opentrack_backend(OpenTrackOptions options = {});

/// Parses "opentrack" or "opentrack:PORT" (the `--device` spec) into options.
Result<OpenTrackOptions> parse_opentrack_spec(const std::string& spec);

}  // namespace sculpt::hal
