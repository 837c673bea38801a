// spnav backend: a client of spacenavd through libspnav.
// Implements: daemon detection, the device name, path and USB id the daemon
// reports, motion as 6 kAxis + kSync, buttons, removal when the daemon
// reports the device gone or closes its socket.
// Lacks: several devices at once (libspnav has one global connection and
// spacenavd merges all devices into it), LEDs, the daemon's own config.

#include "sculpt/hal/backends/spnav_backend.h"

#include "backends/not_built_backend.h"

#if SCULPT_HAL_HAVE_SPNAV
#include <poll.h>
#include <spnav.h>
#include <sys/stat.h>

#include <atomic>
#include <cstdlib>
#include <deque>
#include <memory>

#include "sculpt/hal/types/clock.h"
#endif

namespace sculpt::hal {
namespace {

#if SCULPT_HAL_HAVE_SPNAV

constexpr const char* kNoDaemon = "spacenavd is not running: no connection to its socket";

// libspnav connects to $SPNAV_SOCKET, else /var/run/spnav.sock. Looking for
// the socket first answers "no daemon" without calling spnav_open(), which
// leaks its connection state when the connect fails.
bool daemon_socket_exists() {
  const char* env = std::getenv("SPNAV_SOCKET");
  struct stat st {};
  return ::stat(env && *env ? env : "/var/run/spnav.sock", &st) == 0 && S_ISSOCK(st.st_mode);
}

bool connect_daemon() {
  return daemon_socket_exists() && spnav_open() != -1;
}

// libspnav keeps one process-wide connection: while a device reads through
// it, nothing else may call into the library.
std::atomic<bool> g_connection_in_use{false};

DeviceInfo query_device() {
  DeviceInfo info;
  info.backend = "spnav";
  info.path = "spnav";
  char buf[256] = {};
  if (spnav_dev_name(buf, sizeof buf) > 0) info.name = buf;
  if (info.name.empty()) info.name = "spacenavd device";
  char path[256] = {};
  if (spnav_dev_path(path, sizeof path) > 0)
    info.manufacturer = std::string("via spacenavd, ") + path;
  unsigned vid = 0, pid = 0;
  if (spnav_dev_usbid(&vid, &pid) == 0) {
    info.vendor_id = static_cast<uint16_t>(vid);
    info.product_id = static_cast<uint16_t>(pid);
  }
  return info;
}

class SpnavDevice final : public Device {
 public:
  explicit SpnavDevice(DeviceInfo info) : info_(std::move(info)) {}
  ~SpnavDevice() override {
    spnav_close();
    g_connection_in_use.store(false);
  }
  const DeviceInfo& info() const override { return info_; }

  ReadResult read(RawEvent& out, int timeout_ms) override {
    if (pending_.empty() && !gone_) fill(timeout_ms);
    if (!pending_.empty()) {
      out = pending_.front();
      pending_.pop_front();
      return ReadResult::kEvent;
    }
    if (gone_) {
      out = RawEvent::removed(gone_t_ns_);
      return ReadResult::kRemoved;
    }
    return ReadResult::kTimeout;
  }

 private:
  void fill(int timeout_ms) {
    pollfd p{spnav_fd(), POLLIN, 0};
    const int r = ::poll(&p, 1, timeout_ms);
    const int64_t t = monotonic_ns();
    if (r <= 0) return;
    spnav_event ev;
    int got = 0;
    while (spnav_poll_event(&ev) != 0) {
      ++got;
      switch (ev.type) {
        case SPNAV_EVENT_MOTION: {
          const int v[6] = {ev.motion.x,  ev.motion.y,  ev.motion.z,
                            ev.motion.rx, ev.motion.ry, ev.motion.rz};
          for (int i = 0; i < 6; ++i)
            pending_.push_back(RawEvent::axis(t, i, v[i]));
          pending_.push_back(RawEvent::sync(t));
          break;
        }
        case SPNAV_EVENT_BUTTON:
          pending_.push_back(RawEvent::button(t, ev.button.bnum, ev.button.press != 0));
          break;
        case SPNAV_EVENT_DEV:
          if (ev.dev.op == SPNAV_DEV_RM) mark_gone(t);
          break;
        default:
          break;
      }
    }
    // Readable with nothing to read: the daemon closed the socket.
    if (got == 0 && (p.revents & (POLLHUP | POLLERR | POLLIN))) mark_gone(t);
  }
  void mark_gone(int64_t t) {
    gone_ = true;
    gone_t_ns_ = t;
  }

  DeviceInfo info_;
  std::deque<RawEvent> pending_;
  bool gone_ = false;
  int64_t gone_t_ns_ = 0;
};

class SpnavBackend final : public Backend {
 public:
  std::string_view name() const override { return "spnav"; }

  BackendStatus status() override {
    if (g_connection_in_use.load()) return {};
    if (!connect_daemon()) return {BackendState::kUnavailable, kNoDaemon};
    spnav_close();
    return {};
  }

  Result<std::vector<DeviceInfo>> enumerate() override {
    if (g_connection_in_use.load()) return std::vector<DeviceInfo>{cached_};
    if (!connect_daemon()) return Error(std::string("spnav: ") + kNoDaemon);
    // Protocol 0 daemons (before 1.0) cannot describe the device: assume one.
    const bool described = spnav_protocol() >= 1;
    DeviceInfo info = described ? query_device() : DeviceInfo{};
    if (!described) {
      info.backend = "spnav";
      info.path = "spnav";
      info.name = "spacenavd device";
    }
    const int axes = described ? spnav_dev_axes() : 6;
    spnav_close();
    std::vector<DeviceInfo> out;
    // A daemon with no device reports no axes (or an empty name).
    if (axes > 0) out.push_back(info);
    return out;
  }

  Result<std::unique_ptr<Device>> open(const DeviceInfo& info) override {
    bool expected = false;
    if (!g_connection_in_use.compare_exchange_strong(expected, true)) {
      return Error(info.id() + ": already open (libspnav has one connection per process)");
    }
    if (!connect_daemon()) {
      g_connection_in_use.store(false);
      return Error(info.id() + ": " + kNoDaemon);
    }
    spnav_client_name("sculpt");
    cached_ = spnav_protocol() >= 1 ? query_device() : info;
    return std::unique_ptr<Device>(std::make_unique<SpnavDevice>(cached_));
  }

 private:
  DeviceInfo cached_;
};

#endif

}  // namespace

std::unique_ptr<Backend> make_spnav_backend() {
#if SCULPT_HAL_HAVE_SPNAV
  return std::make_unique<SpnavBackend>();
#else
  return detail::make_not_built_backend("spnav", "SCULPT_WITH_SPNAV", "libspnav-dev");
#endif
}

}  // namespace sculpt::hal
