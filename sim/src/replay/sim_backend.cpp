#include "sculpt/sim/replay/sim_backend.h"

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
};

namespace {

class SimDevice final : public hal::Device {
 public:
  SimDevice(std::shared_ptr<SimBackend::Shared> shared, hal::DeviceInfo info)
      : shared_(std::move(shared)),
        info_(std::move(info)),
        player_(std::make_unique<SessionPlayer>(shared_->session, shared_->speed)) {}
  const hal::DeviceInfo& info() const override { return info_; }

  hal::ReadResult read(hal::RawEvent& out, int timeout_ms) override {
    if (removed_) {
      out = hal::RawEvent::removed(last_t_ns_);
      return hal::ReadResult::kRemoved;
    }
    // Never wait past the timeout: a pause in the recording must not keep the
    // reader thread from noticing that it should stop.
    const int64_t deadline = player_->clock().now_ns() + int64_t{timeout_ms} * 1'000'000;
    if (player_->at_end() && shared_->loop) next_round();
    while (!player_->at_end()) {
      if (player_->due_ns() > deadline) {
        player_->clock().sleep_until_ns(deadline);
        return hal::ReadResult::kTimeout;
      }
      const SessionRecord* r = player_->next();
      if (r == nullptr) break;
      last_t_ns_ = r->t_ns() + offset_ns_;
      // A force device's loop is not this device's: a live play moves the
      // tool through the commands it recorded.
      if (r->kind == SessionRecord::Kind::kHaptic) continue;
      if (r->kind == SessionRecord::Kind::kCommand) {
        std::lock_guard lock(shared_->mutex);
        shared_->commands.emplace_back(last_t_ns_, r->command);
        continue;
      }
      out = r->event;
      out.t_ns = last_t_ns_;
      if (out.kind == hal::RawEventKind::kRemoved) {
        removed_ = true;
        return hal::ReadResult::kRemoved;
      }
      return hal::ReadResult::kEvent;
    }
    // The recording is over: the device stays connected and quiet.
    // (A looping device is never played out: the next read starts again.)
    if (!shared_->loop) shared_->played.store(true);
    player_->clock().sleep_until_ns(deadline);
    return hal::ReadResult::kTimeout;
  }

 private:
  // The session again from its start, a second after the last round ended.
  void next_round() {
    const Session& s = shared_->session;
    offset_ns_ += s.end_t_ns() - s.start_t_ns() + 1'000'000'000;
    player_ = std::make_unique<SessionPlayer>(s, shared_->speed);
  }

  std::shared_ptr<SimBackend::Shared> shared_;
  hal::DeviceInfo info_;
  std::unique_ptr<SessionPlayer> player_;
  bool removed_ = false;
  int64_t last_t_ns_ = 0;
  int64_t offset_ns_ = 0;  // added to every time after the first round
};

}  // namespace

SimBackend::SimBackend(Session session, std::string path, double speed, bool loop)
    : shared_(std::make_shared<Shared>()) {
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
  return std::exchange(changed_, false);
}

bool SimBackend::played() const {
  return shared_->played.load();
}

std::vector<std::pair<int64_t, Command>> SimBackend::take_commands() {
  std::lock_guard lock(shared_->mutex);
  return std::exchange(shared_->commands, {});
}

}  // namespace sculpt::sim
