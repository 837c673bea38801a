#include "sculpt/sim/replay/sim_backend.h"

#include <algorithm>
#include <atomic>

#include "sculpt/sim/replay/session_player.h"

namespace sculpt::sim {

struct SimBackend::Shared {
  Session session;
  double speed;
  bool loop = false;
  std::mutex mutex;
  std::vector<std::pair<int64_t, Command>> commands;
  bool opened = false;
  std::atomic<bool> played{false};  // every record handed out
  // Where the session is: kept here, not in the device, so that after a
  // recorded unplug the device opened again (the registry's next scan, as a
  // real device plugged back in) plays on from the record after it, as
  // `sculpt replay` does.
  std::unique_ptr<SessionPlayer> player;
  int64_t last_t_ns = 0;
  int64_t offset_ns = 0;               // added to every time after the first round
  std::atomic<bool> unplugged{false};  // since changed() last said so
  // False until start_playing() for a backend made to wait: the player is
  // made paused and resumed (its pacing restarted) by the first read after.
  std::atomic<bool> started{true};
};

namespace {

using Shared = SimBackend::Shared;

// How often a device waiting for start_playing() looks again.
constexpr int64_t kStartPollNs = 1'000'000;

class SimDevice final : public hal::Device {
 public:
  // One device at a time reads the shared player (SimBackend::open()).
  SimDevice(std::shared_ptr<SimBackend::Shared> shared, hal::DeviceInfo info)
      : shared_(std::move(shared)), info_(std::move(info)) {
    if (!shared_->player) {
      shared_->player = std::make_unique<SessionPlayer>(shared_->session, shared_->speed);
      if (!shared_->started.load()) shared_->player->pause();
    }
  }
  const hal::DeviceInfo& info() const override { return info_; }

  hal::ReadResult read(hal::RawEvent& out, int timeout_ms) override {
    Shared& sh = *shared_;
    if (removed_) {
      out = hal::RawEvent::removed(removed_t_ns_);
      return hal::ReadResult::kRemoved;
    }
    // Never wait past the timeout: a pause in the recording must not keep the
    // reader thread from noticing that it should stop.
    const int64_t deadline = sh.player->clock().now_ns() + int64_t{timeout_ms} * 1'000'000;
    if (!sh.started.load(std::memory_order_acquire)) {
      // Not started: looked at again within a millisecond, so that the
      // session starts when the station does.
      sh.player->clock().sleep_until_ns(
          std::min(deadline, sh.player->clock().now_ns() + kStartPollNs));
      return hal::ReadResult::kTimeout;
    }
    if (sh.player->paused()) sh.player->resume();  // started: the clock runs from now
    if (sh.player->at_end() && sh.loop) next_round();
    SessionPlayer& player = *sh.player;
    while (!player.at_end()) {
      if (player.due_ns() > deadline) {
        player.clock().sleep_until_ns(deadline);
        return hal::ReadResult::kTimeout;
      }
      const SessionRecord* r = player.next();
      if (r == nullptr) break;
      sh.last_t_ns = r->t_ns() + sh.offset_ns;
      // A force device's loop is not this device's: a live play moves the
      // tool through the commands it recorded.
      if (r->kind == SessionRecord::Kind::kHaptic) continue;
      if (r->kind == SessionRecord::Kind::kCommand) {
        std::lock_guard lock(sh.mutex);
        sh.commands.emplace_back(sh.last_t_ns, r->command);
        continue;
      }
      out = r->event;
      out.t_ns = sh.last_t_ns;
      if (out.kind == hal::RawEventKind::kRemoved) {
        // Unplugged: this handle is gone; the backend lists the device
        // again and the next open plays on (or, the session over, nothing).
        removed_ = true;
        removed_t_ns_ = sh.last_t_ns;
        if (player.at_end() && !sh.loop) sh.played.store(true);
        {
          std::lock_guard lock(sh.mutex);
          sh.opened = false;
        }
        sh.unplugged.store(true);
        return hal::ReadResult::kRemoved;
      }
      return hal::ReadResult::kEvent;
    }
    // The recording is over: the device stays connected and quiet.
    // (A looping device is never played out: the next read starts again.)
    if (!sh.loop) sh.played.store(true);
    player.clock().sleep_until_ns(deadline);
    return hal::ReadResult::kTimeout;
  }

 private:
  // The session again from its start, a second after the last round ended.
  void next_round() {
    const Session& s = shared_->session;
    shared_->offset_ns += s.end_t_ns() - s.start_t_ns() + 1'000'000'000;
    shared_->player = std::make_unique<SessionPlayer>(s, shared_->speed);
  }

  std::shared_ptr<SimBackend::Shared> shared_;
  hal::DeviceInfo info_;
  bool removed_ = false;
  int64_t removed_t_ns_ = 0;  // the shared state is the next handle's then
};

}  // namespace

SimBackend::SimBackend(Session session, std::string path, double speed, bool loop,
                       bool wait_for_start)
    : shared_(std::make_shared<Shared>()) {
  shared_->started.store(!wait_for_start);
  info_ = session.header.device;
  info_.backend = "sim";
  info_.path = std::move(path);
  shared_->session = std::move(session);
  shared_->speed = speed;
  shared_->loop = loop;
}

Result<std::vector<hal::DeviceInfo>> SimBackend::enumerate() {
  return std::vector<hal::DeviceInfo>{info_};
}

Result<std::unique_ptr<hal::Device>> SimBackend::open(const hal::DeviceInfo& info) {
  if (info.path != info_.path) return Error("sim:" + info.path + ": no such session device");
  std::lock_guard lock(shared_->mutex);
  if (shared_->opened) return Error("sim:" + info.path + ": already open");
  shared_->opened = true;
  return std::unique_ptr<hal::Device>(std::make_unique<SimDevice>(shared_, info_));
}

bool SimBackend::changed() {
  const bool unplugged = shared_->unplugged.exchange(false);
  return std::exchange(changed_, false) || unplugged;
}

bool SimBackend::played() const {
  return shared_->played.load();
}

void SimBackend::start_playing() {
  shared_->started.store(true, std::memory_order_release);
}

std::vector<std::pair<int64_t, Command>> SimBackend::take_commands() {
  std::lock_guard lock(shared_->mutex);
  return std::exchange(shared_->commands, {});
}

}  // namespace sculpt::sim
