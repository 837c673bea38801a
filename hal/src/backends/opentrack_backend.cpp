// opentrack backend: a UDP receiver of OpenTrack's "UDP over network" output.
// Implements: loopback-only binding by default, a non-blocking socket
// drained to the newest datagram on every read (OpenTrack sends at its
// tracker's rate, up to ~250 Hz; only the newest pose matters, DESIGN.md
// §5 "motion is state"), sender lock-in, counting of every dropped
// datagram by cause, "tracking lost" after a silence.
// Lacks: IPv6 listen addresses, several senders on one port (one port is
// one tracker), a name lookup for the listen address.

#include "sculpt/hal/backends/opentrack_backend.h"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cstring>

#include "backends/tracker_listing_backend.h"
#include "sculpt/hal/parsers/opentrack_datagram.h"
#include "sculpt/hal/types/clock.h"

namespace sculpt::hal {
namespace {

// A drain stops after this many datagrams even if more are queued, so a
// flood cannot keep the reader thread from delivering anything.
constexpr int kMaxDatagramsPerDrain = 4096;

std::string endpoint_text(uint32_t ip_net, uint16_t port_net) {
  char buf[INET_ADDRSTRLEN] = {};
  in_addr a{};
  a.s_addr = ip_net;
  ::inet_ntop(AF_INET, &a, buf, sizeof buf);
  return std::string(buf) + ":" + std::to_string(ntohs(port_net));
}

// The path is the port asked for (the id `--device opentrack:PORT` names);
// the name shows the port really bound (they differ for port 0).
DeviceInfo opentrack_device_info(const OpenTrackOptions& options, uint16_t bound_port) {
  DeviceInfo info;
  info.backend = "opentrack";
  info.path = std::to_string(options.port);
  info.name = "OpenTrack UDP on " + options.listen_address + ":" + std::to_string(bound_port);
  info.serial = "opentrack:" + info.path;  // the physical key: one listener per port
  return info;
}

}  // namespace

OpenTrackDevice::OpenTrackDevice(int fd, uint16_t port, const OpenTrackOptions& options)
    : fd_(fd),
      bound_port_(port),
      lost_after_ns_(static_cast<int64_t>(options.lost_after_ms) * 1'000'000),
      info_(opentrack_device_info(options, port)) {}

OpenTrackDevice::~OpenTrackDevice() {
  if (fd_ >= 0) ::close(fd_);
}

Result<std::unique_ptr<OpenTrackDevice>> OpenTrackDevice::open(const OpenTrackOptions& options) {
  const std::string where = options.listen_address + ":" + std::to_string(options.port);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_port = htons(options.port);
  if (::inet_pton(AF_INET, options.listen_address.c_str(), &addr.sin_addr) != 1)
    return Error(where + ": not an IPv4 listen address");
  const int fd = ::socket(AF_INET, SOCK_DGRAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
  if (fd < 0) return Error(where + ": socket: " + std::strerror(errno));
  if (::bind(fd, reinterpret_cast<const sockaddr*>(&addr), sizeof addr) != 0) {
    const int e = errno;
    ::close(fd);
    return Error(where + ": " + std::strerror(e));
  }
  sockaddr_in bound{};
  socklen_t len = sizeof bound;
  ::getsockname(fd, reinterpret_cast<sockaddr*>(&bound), &len);
  return std::unique_ptr<OpenTrackDevice>(new OpenTrackDevice(fd, ntohs(bound.sin_port), options));
}

std::string OpenTrackDevice::locked_sender() const {
  return sender_locked_ ? endpoint_text(sender_ip_, sender_port_) : std::string();
}

bool OpenTrackDevice::drain(RawEvent& newest, int64_t now_ns) {
  bool have = false;
  // One byte more than a datagram, and MSG_TRUNC gives the real length, so
  // a long datagram is seen as long rather than cut to look right.
  uint8_t buf[kOpenTrackDatagramBytes + 1];
  for (int i = 0; i < kMaxDatagramsPerDrain; ++i) {
    sockaddr_in from{};
    socklen_t from_len = sizeof from;
    const ssize_t n = ::recvfrom(fd_, buf, sizeof buf, MSG_TRUNC | MSG_DONTWAIT,
                                 reinterpret_cast<sockaddr*>(&from), &from_len);
    if (n < 0) break;  // EAGAIN: drained (other errors: nothing to read either)
    ++counters_.datagrams;
    if (sender_locked_ && (from.sin_addr.s_addr != sender_ip_ || from.sin_port != sender_port_)) {
      ++counters_.foreign_sender;
      continue;
    }
    // A datagram longer than buf shows as sizeof buf bytes: still long.
    const auto bytes = std::span<const uint8_t>(buf, std::min(static_cast<size_t>(n), sizeof buf));
    TrackerPose pose;
    switch (decode_opentrack_datagram(bytes, pose)) {
      case OpenTrackDatagramError::kShort:
        ++counters_.short_datagrams;
        continue;
      case OpenTrackDatagramError::kLong:
        ++counters_.long_datagrams;
        continue;
      case OpenTrackDatagramError::kNotFinite:
        ++counters_.not_finite;
        continue;
      case OpenTrackDatagramError::kNone:
        break;
    }
    if (!sender_locked_) {
      sender_locked_ = true;
      sender_ip_ = from.sin_addr.s_addr;
      sender_port_ = from.sin_port;
    }
    if (have) ++counters_.superseded;
    newest = RawEvent::report(now_ns, bytes);
    have = true;
  }
  return have;
}

ReadResult OpenTrackDevice::read(RawEvent& out, int timeout_ms) {
  int64_t now = monotonic_ns();
  timeout_ms = std::max(timeout_ms, 0);
  // Wake up in time to report a loss even when the caller waits longer.
  if (tracking_) {
    const int64_t until_lost_ms = (last_good_ns_ + lost_after_ns_ - now + 999'999) / 1'000'000;
    timeout_ms = static_cast<int>(std::clamp<int64_t>(until_lost_ms, 0, timeout_ms));
  }
  pollfd p{fd_, POLLIN, 0};
  if (::poll(&p, 1, timeout_ms) > 0) {
    now = monotonic_ns();
    if (drain(out, now)) {
      ++counters_.accepted;
      tracking_ = true;
      last_good_ns_ = now;
      return ReadResult::kEvent;
    }
  }
  now = monotonic_ns();
  if (tracking_ && now - last_good_ns_ >= lost_after_ns_) {
    tracking_ = false;
    ++counters_.tracking_lost;
    out = RawEvent::report(now, {});
    return ReadResult::kEvent;
  }
  return ReadResult::kTimeout;
}

std::unique_ptr<Backend> make_opentrack_backend(OpenTrackOptions options) {
  return detail::make_tracker_listing_backend(
      opentrack_device_info(options, options.port), [options]() -> Result<std::unique_ptr<Device>> {
        auto device = OpenTrackDevice::open(options);
        if (!device) return device.error();
        return std::unique_ptr<Device>(std::move(device).value());
      });
}

Result<OpenTrackOptions> parse_opentrack_spec(const std::string& spec) {
  OpenTrackOptions options;
  if (spec == "opentrack") return options;
  constexpr std::string_view kHead = "opentrack:";
  if (spec.rfind(kHead, 0) != 0) return Error(spec + ": not an opentrack[:PORT] device");
  const std::string port = spec.substr(kHead.size());
  unsigned value = 0;
  const auto [end, ec] = std::from_chars(port.data(), port.data() + port.size(), value);
  if (ec != std::errc() || end != port.data() + port.size() || value == 0 || value > 65535)
    return Error(spec + ": port '" + port + "' is not a number from 1 to 65535");
  options.port = static_cast<uint16_t>(value);
  return options;
}

}  // namespace sculpt::hal
