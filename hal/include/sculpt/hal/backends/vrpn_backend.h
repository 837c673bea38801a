#pragma once
// vrpn: a client of one tracker on a VRPN server (`vrpn:NAME@HOST[:PORT]`,
// default port 3883), over TCP only (VRPN's "tcp://" mode: no UDP, no
// callback connection from the server), connecting only to the host given.
//
// Each Pos_Quat message of the tracker NAME becomes one kReport RawEvent
// holding its 64-byte payload as it arrived (sensor, position, quaternion),
// so a session records it and a replay decodes the same pose
// (decode_vrpn_pos_quat). Several sensors arrive as reports of their own;
// within one read only the newest report per sensor is kept. A kReport with
// no bytes means "tracking lost": the connection ended after poses came.
//
// The connection runs inside read() without ever blocking past its timeout:
// a non-blocking connect, the cookie exchange (with a deadline, so a server
// that stalls is dropped), then messages. When the server goes away the
// device reconnects with a backoff that doubles up to backoff_max_ms; each
// end of a connection is one log line.
//
// Thread safety: as every Device, read by one thread; counters() from that
// thread only.

#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "sculpt/hal/types/device.h"

namespace sculpt::hal {

inline constexpr uint16_t kVrpnDefaultPort = 3883;

struct VrpnOptions {
  std::string tracker;  ///< the sender name on the server, e.g. "Tracker0"
  std::string host;     ///< name or address; the only host ever contacted
  uint16_t port = kVrpnDefaultPort;
  int connect_timeout_ms = 2000;  ///< for the TCP connect
  int cookie_timeout_ms = 2000;   ///< from connected to the server's cookie
  int backoff_initial_ms = 250;   ///< first wait before reconnecting
  int backoff_max_ms = 4000;      ///< the wait doubles up to this
  /// Where the one line per ended connection goes; stderr when empty.
  std::function<void(std::string_view)> log;
};

/// Parses "vrpn:NAME@HOST" or "vrpn:NAME@HOST:PORT".
Result<VrpnOptions> parse_vrpn_spec(const std::string& spec);

struct VrpnCounters {
  int64_t connects = 0;     ///< cookie exchanges completed
  int64_t disconnects = 0;  ///< connections ended (by the server or for bad input)
  int64_t failed_connects = 0;
  int64_t messages = 0;         ///< framed messages received
  int64_t poses = 0;            ///< Pos_Quat reports delivered
  int64_t superseded = 0;       ///< Pos_Quat of a sensor replaced by a newer one before delivery
  int64_t other_types = 0;      ///< user messages not Pos_Quat (velocity, buttons, ...)
  int64_t other_senders = 0;    ///< Pos_Quat from another tracker on the same server
  int64_t system_messages = 0;  ///< system messages other than descriptions
  int64_t bad_descriptions = 0;
  int64_t bad_poses = 0;      ///< short, long, NaN, negative sensor, zero quaternion
  int64_t bad_cookies = 0;    ///< connection ended: not a VRPN 07 server
  int64_t bad_lengths = 0;    ///< connection ended: unframeable length
  int64_t stalls = 0;         ///< connection ended: no cookie in time, or connect timed out
  int64_t tracking_lost = 0;  ///< "lost" reports delivered
};

class VrpnTrackerDevice final : public Device {
 public:
  ~VrpnTrackerDevice() override;
  /// Checks the options; the connection starts at the first read().
  static Result<std::unique_ptr<VrpnTrackerDevice>> open(VrpnOptions options);

  const DeviceInfo& info() const override { return info_; }
  /// Never kRemoved: a server that went away may come back.
  ReadResult read(RawEvent& out, int timeout_ms) override;

  const VrpnCounters& counters() const { return counters_; }
  bool streaming() const { return state_ == State::kStreaming; }

 private:
  enum class State { kIdle, kConnecting, kCookie, kStreaming };
  explicit VrpnTrackerDevice(VrpnOptions options);
  void start_connect(int64_t now_ns);
  void on_connected(int64_t now_ns);
  void receive(int64_t now_ns);
  void take_messages(int64_t now_ns);
  void handle(int32_t sender, int32_t type, std::span<const uint8_t> payload, int64_t now_ns);
  void queue_pose(std::span<const uint8_t> payload, int64_t now_ns);
  void drop(const std::string& why, int64_t now_ns);
  void log(const std::string& line);

  VrpnOptions options_;
  DeviceInfo info_;
  VrpnCounters counters_;
  State state_ = State::kIdle;
  int fd_ = -1;
  int64_t retry_at_ns_ = 0;
  int64_t state_deadline_ns_ = 0;  // kConnecting / kCookie
  int backoff_ms_ = 0;
  std::string last_failure_;  // repeated connect failures are logged once
  std::vector<uint8_t> inbuf_;
  int32_t tracker_sender_ = -1;
  int32_t pos_quat_type_ = -1;
  bool tracking_ = false;  // a pose came on this connection
  std::deque<RawEvent> pending_;
};

/// A backend with the one tracker of `options`. enumerate() lists it
/// without connecting (trackers are opened only when asked for).
std::unique_ptr<Backend> make_vrpn_backend(VrpnOptions options);

}  // namespace sculpt::hal
