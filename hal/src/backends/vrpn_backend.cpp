// vrpn backend: a TCP client of one tracker on a VRPN server, written from
// the published protocol (see parsers/vrpn_message.cpp for where each part
// was checked).
// Implements: VRPN's TCP-only mode (the client connects to the server's
// port, as vrpn_Connection_IP does for "tcp://host:port"), the cookie
// exchange both ways, the server's sender and type descriptions (ids are the
// server's, fresh on every connection), Pos_Quat of the named tracker, all
// its sensors, reconnection with a doubling backoff.
// Lacks: UDP (VRPN's default: the server connects back to the client, which
// a loopback-safe client should not accept), clock synchronisation (the
// report's time is its arrival), velocity/acceleration messages (counted as
// other types), remote logging. The host name is resolved with a blocking
// getaddrinfo() at each connect attempt.

#include "sculpt/hal/backends/vrpn_backend.h"

#include <fcntl.h>
#include <netdb.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cstdio>
#include <cstring>

#include "backends/tracker_listing_backend.h"
#include "sculpt/hal/parsers/vrpn_message.h"
#include "sculpt/hal/types/clock.h"

namespace sculpt::hal {
namespace {

constexpr int64_t kNsPerMs = 1'000'000;
// Bytes taken from the socket per recv(); a full-rate tracker sends far less.
constexpr size_t kRecvChunkBytes = 16 * 1024;

int ms_until(int64_t deadline_ns, int64_t now_ns) {
  if (deadline_ns <= now_ns) return 0;
  return static_cast<int>(
      std::min<int64_t>((deadline_ns - now_ns + kNsPerMs - 1) / kNsPerMs, 1'000'000));
}

// Sends everything or fails; the socket is non-blocking, and the few bytes
// a client sends fit a fresh socket's buffer, so a short write means trouble.
bool send_all(int fd, std::span<const uint8_t> bytes) {
  const ssize_t n = ::send(fd, bytes.data(), bytes.size(), MSG_NOSIGNAL);
  return n == static_cast<ssize_t>(bytes.size());
}

DeviceInfo vrpn_device_info(const VrpnOptions& options) {
  DeviceInfo info;
  info.backend = "vrpn";
  info.path = options.tracker + "@" + options.host + ":" + std::to_string(options.port);
  info.name = "VRPN tracker " + info.path;
  info.serial = "vrpn:" + info.path;  // the physical key: one client per tracker and server
  return info;
}

}  // namespace

Result<VrpnOptions> parse_vrpn_spec(const std::string& spec) {
  constexpr std::string_view kHead = "vrpn:";
  if (spec.rfind(kHead, 0) != 0) return Error(spec + ": not a vrpn:NAME@HOST[:PORT] device");
  const std::string rest = spec.substr(kHead.size());
  const size_t at = rest.rfind('@');
  if (at == std::string::npos || at == 0)
    return Error(spec + ": want vrpn:NAME@HOST[:PORT] (the tracker's name, then its host)");
  VrpnOptions o;
  o.tracker = rest.substr(0, at);
  std::string host = rest.substr(at + 1);
  const size_t colon = host.rfind(':');
  if (colon != std::string::npos && host.find(':') == colon) {  // not a bare IPv6 address
    const std::string port = host.substr(colon + 1);
    unsigned value = 0;
    const auto [end, ec] = std::from_chars(port.data(), port.data() + port.size(), value);
    if (ec != std::errc() || end != port.data() + port.size() || value == 0 || value > 65535)
      return Error(spec + ": port '" + port + "' is not a number from 1 to 65535");
    o.port = static_cast<uint16_t>(value);
    host = host.substr(0, colon);
  }
  if (host.empty()) return Error(spec + ": no host after '@'");
  if (o.tracker.size() + 1 > kVrpnMaxNameBytes)
    return Error(spec + ": tracker name longer than VRPN's 99 characters");
  o.host = host;
  return o;
}

VrpnTrackerDevice::VrpnTrackerDevice(VrpnOptions options)
    : options_(std::move(options)),
      info_(vrpn_device_info(options_)),
      backoff_ms_(options_.backoff_initial_ms) {}

VrpnTrackerDevice::~VrpnTrackerDevice() {
  if (fd_ >= 0) ::close(fd_);
}

Result<std::unique_ptr<VrpnTrackerDevice>> VrpnTrackerDevice::open(VrpnOptions options) {
  if (options.tracker.empty() || options.host.empty())
    return Error("vrpn: a tracker needs a name and a host (vrpn:NAME@HOST[:PORT])");
  return std::unique_ptr<VrpnTrackerDevice>(new VrpnTrackerDevice(std::move(options)));
}

void VrpnTrackerDevice::log(const std::string& line) {
  const std::string full = "vrpn: " + info_.path + ": " + line;
  if (options_.log) {
    options_.log(full);
  } else {
    std::fprintf(stderr, "%s\n", full.c_str());
  }
}

void VrpnTrackerDevice::start_connect(int64_t now_ns) {
  addrinfo hints{};
  hints.ai_family = AF_UNSPEC;
  hints.ai_socktype = SOCK_STREAM;
  addrinfo* found = nullptr;
  const std::string port = std::to_string(options_.port);
  const int gai = ::getaddrinfo(options_.host.c_str(), port.c_str(), &hints, &found);
  if (gai != 0 || !found) {
    state_ = State::kConnecting;  // so drop() treats it as a failed attempt
    drop(std::string("cannot resolve host: ") + ::gai_strerror(gai), now_ns);
    return;
  }
  fd_ = ::socket(found->ai_family, found->ai_socktype | SOCK_NONBLOCK | SOCK_CLOEXEC,
                 found->ai_protocol);
  int r = fd_ < 0 ? -1 : ::connect(fd_, found->ai_addr, found->ai_addrlen);
  const int e = errno;
  ::freeaddrinfo(found);
  state_ = State::kConnecting;
  state_deadline_ns_ = now_ns + int64_t{options_.connect_timeout_ms} * kNsPerMs;
  if (fd_ < 0 || (r != 0 && e != EINPROGRESS)) {
    drop(std::string("connect: ") + std::strerror(e), now_ns);
    return;
  }
  if (r == 0) on_connected(now_ns);
}

void VrpnTrackerDevice::on_connected(int64_t now_ns) {
  const int one = 1;
  ::setsockopt(fd_, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);  // poses are small and urgent
  if (!send_all(fd_, make_vrpn_cookie())) {
    drop("cannot send the cookie", now_ns);
    return;
  }
  state_ = State::kCookie;
  state_deadline_ns_ = now_ns + int64_t{options_.cookie_timeout_ms} * kNsPerMs;
}

void VrpnTrackerDevice::drop(const std::string& why, int64_t now_ns) {
  const bool was_connected = state_ == State::kCookie || state_ == State::kStreaming;
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  inbuf_.clear();
  tracker_sender_ = -1;
  pos_quat_type_ = -1;
  if (was_connected) {
    ++counters_.disconnects;
    last_failure_.clear();
  } else {
    ++counters_.failed_connects;
  }
  // One line per connection that ends; a server that stays down is
  // reported once, not at every retry.
  if (was_connected || why != last_failure_) {
    log(why + "; retrying in " + std::to_string(backoff_ms_) + " ms");
    if (!was_connected) last_failure_ = why;
  }
  if (tracking_) {
    tracking_ = false;
    ++counters_.tracking_lost;
    pending_.push_back(RawEvent::report(now_ns, {}));
  }
  state_ = State::kIdle;
  retry_at_ns_ = now_ns + int64_t{backoff_ms_} * kNsPerMs;
  backoff_ms_ = std::min(backoff_ms_ * 2, options_.backoff_max_ms);
}

void VrpnTrackerDevice::receive(int64_t now_ns) {
  const size_t had = inbuf_.size();
  inbuf_.resize(had + kRecvChunkBytes);
  const ssize_t n = ::recv(fd_, inbuf_.data() + had, kRecvChunkBytes, MSG_DONTWAIT);
  inbuf_.resize(had + (n > 0 ? static_cast<size_t>(n) : 0));
  if (n == 0) {
    drop("the server closed the connection", now_ns);
    return;
  }
  if (n < 0) {
    if (errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR)
      drop(std::string("receive: ") + std::strerror(errno), now_ns);
    return;
  }
  if (state_ == State::kCookie) {
    if (inbuf_.size() < kVrpnCookieBytes) return;
    if (check_vrpn_cookie(inbuf_) != VrpnCookieError::kNone) {
      ++counters_.bad_cookies;
      drop("not a VRPN 07 server (bad cookie)", now_ns);
      return;
    }
    inbuf_.erase(inbuf_.begin(), inbuf_.begin() + kVrpnCookieBytes);
    // Like any VRPN client, say who we are: our sender (the tracker's name)
    // and the one type we listen to, with our own ids 0 and 0.
    std::vector<uint8_t> hello =
        encode_vrpn_message(0, kVrpnSenderDescription, encode_vrpn_description(options_.tracker));
    const std::vector<uint8_t> type =
        encode_vrpn_message(0, kVrpnTypeDescription, encode_vrpn_description(kVrpnPosQuatType));
    hello.insert(hello.end(), type.begin(), type.end());
    if (!send_all(fd_, hello)) {
      drop("cannot send the descriptions", now_ns);
      return;
    }
    state_ = State::kStreaming;
    ++counters_.connects;
    backoff_ms_ = options_.backoff_initial_ms;
    last_failure_.clear();
  }
  take_messages(now_ns);
}

void VrpnTrackerDevice::take_messages(int64_t now_ns) {
  size_t at = 0;
  while (state_ == State::kStreaming) {
    VrpnMessage m;
    const VrpnFrameResult r = next_vrpn_message(std::span(inbuf_).subspan(at), m);
    if (r == VrpnFrameResult::kNeedMore) break;
    if (r == VrpnFrameResult::kBadLength) {
      ++counters_.bad_lengths;
      drop("message length " + std::to_string(m.length) + " outside 24.." +
               std::to_string(kVrpnMaxMessageBytes) + " bytes: the stream is lost",
           now_ns);
      return;  // drop() cleared the buffer
    }
    ++counters_.messages;
    handle(m.sender, m.type, m.payload, now_ns);
    at += m.consumed;
  }
  inbuf_.erase(inbuf_.begin(), inbuf_.begin() + static_cast<ptrdiff_t>(at));
}

void VrpnTrackerDevice::handle(int32_t sender, int32_t type, std::span<const uint8_t> payload,
                               int64_t now_ns) {
  if (type == kVrpnSenderDescription || type == kVrpnTypeDescription) {
    std::string_view name;
    if (decode_vrpn_description(payload, name) != VrpnPayloadError::kNone) {
      ++counters_.bad_descriptions;
      return;
    }
    if (type == kVrpnSenderDescription && name == options_.tracker) tracker_sender_ = sender;
    if (type == kVrpnTypeDescription && name == kVrpnPosQuatType) pos_quat_type_ = sender;
    return;
  }
  if (type < 0) {
    ++counters_.system_messages;
    return;
  }
  if (type != pos_quat_type_) {
    ++counters_.other_types;
    return;
  }
  if (sender != tracker_sender_) {
    ++counters_.other_senders;
    return;
  }
  queue_pose(payload, now_ns);
}

void VrpnTrackerDevice::queue_pose(std::span<const uint8_t> payload, int64_t now_ns) {
  TrackerPose pose;
  if (decode_vrpn_pos_quat(payload, pose) != VrpnPayloadError::kNone) {
    ++counters_.bad_poses;
    return;
  }
  tracking_ = true;
  const RawEvent e = RawEvent::report(now_ns, payload);
  // Motion is state: a sensor's newer pose replaces one not yet delivered.
  for (RawEvent& queued : pending_) {
    TrackerPose q;
    if (queued.size == kVrpnPosQuatBytes &&
        decode_vrpn_pos_quat(queued.bytes(), q) == VrpnPayloadError::kNone &&
        q.sensor == pose.sensor) {
      queued = e;
      ++counters_.superseded;
      return;
    }
  }
  pending_.push_back(e);
}

ReadResult VrpnTrackerDevice::read(RawEvent& out, int timeout_ms) {
  const int64_t deadline = monotonic_ns() + int64_t{std::max(timeout_ms, 0)} * kNsPerMs;
  for (;;) {
    if (!pending_.empty()) {
      out = pending_.front();
      pending_.pop_front();
      if (out.size > 0) ++counters_.poses;
      return ReadResult::kEvent;
    }
    const int64_t now = monotonic_ns();
    if (state_ == State::kIdle) {
      if (now >= retry_at_ns_) {
        start_connect(now);
        continue;
      }
      const int wait = ms_until(std::min(deadline, retry_at_ns_), now);
      if (wait == 0 && now >= deadline) return ReadResult::kTimeout;
      ::poll(nullptr, 0, wait);
      continue;
    }
    const bool waiting_on_server = state_ != State::kStreaming;
    if (waiting_on_server && now >= state_deadline_ns_) {
      ++counters_.stalls;
      drop(
          state_ == State::kConnecting
              ? "no answer to connect within " + std::to_string(options_.connect_timeout_ms) + " ms"
              : "no cookie within " + std::to_string(options_.cookie_timeout_ms) +
                    " ms (a stalled or non-VRPN server)",
          now);
      continue;
    }
    const int64_t until = waiting_on_server ? std::min(deadline, state_deadline_ns_) : deadline;
    pollfd p{fd_, static_cast<short>(state_ == State::kConnecting ? POLLOUT : POLLIN), 0};
    const int r = ::poll(&p, 1, ms_until(until, now));
    const int64_t after = monotonic_ns();
    if (r > 0) {
      if (state_ == State::kConnecting) {
        int err = 0;
        socklen_t len = sizeof err;
        ::getsockopt(fd_, SOL_SOCKET, SO_ERROR, &err, &len);
        if (err != 0) {
          drop(std::string("connect: ") + std::strerror(err), after);
        } else {
          on_connected(after);
        }
      } else {
        receive(after);
      }
    }
    // Checked after work too: a server flooding messages that are not poses
    // must not hold the reader past its timeout.
    if (after >= deadline && pending_.empty()) return ReadResult::kTimeout;
  }
}

std::unique_ptr<Backend> make_vrpn_backend(VrpnOptions options) {
  return detail::make_tracker_listing_backend(
      vrpn_device_info(options), [options]() -> Result<std::unique_ptr<Device>> {
        auto device = VrpnTrackerDevice::open(options);
        if (!device) return device.error();
        return std::unique_ptr<Device>(std::move(device).value());
      });
}

}  // namespace sculpt::hal
