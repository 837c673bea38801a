#include "sculpt/station/app/input_hub.h"

#include <algorithm>
#include <limits>
#include <thread>

#include "sculpt/base/memory_reuse.h"
#include "sculpt/base/thread_times.h"
#include "sculpt/core/sculpt/stroke.h"
#include "sculpt/core/volume/volume.h"
#include "sculpt/hal/types/clock.h"

namespace sculpt::station {
namespace {

// Bricks whose stroke buffers the sculpting thread has ready when it starts:
// as many as its pool keeps (the demo's 66-voxel ball reaches 112 with its
// first press, the bust's 110-voxel ball several hundred; 3 x 32 KiB each,
// 50 MB in all, from the warmed heap).
constexpr size_t kWarmStrokeBricks = core::kStrokeBufferBricksKept;

}  // namespace

InputHub::InputHub(StationController& controller, std::unique_ptr<hal::DeviceRegistry> registry,
                   sim::SimBackend* sim, std::string normalizer_text, SurfaceMesher& mesher)
    : controller_(controller),
      registry_(std::move(registry)),
      sim_(sim),
      normalizer_text_(std::move(normalizer_text)),
      mesher_(mesher),
      newest_report_t_ns_(std::numeric_limits<int64_t>::min()) {
  last_scan_ns_ = hal::monotonic_ns();
  note_devices();
  // The render thread's commands (under mutex()) come after the input held
  // for an offset or closing.
  controller_.set_input_barrier([this] {
    controller_.land_morphology(/*wait=*/true);
    release_held(hal::monotonic_ns());
  });
}

InputHub::~InputHub() {
  stop();
  controller_.set_input_barrier(nullptr);
}

void InputHub::prepare(size_t warm_heap_bytes) {
  if (thread_.joinable()) return;
  {
    std::lock_guard gate(gate_);
    stop_.store(false, std::memory_order_relaxed);
    warmed_ = false;
    go_ = false;
  }
  // The volume's own bricks (a project may use another edge than the
  // default): read here, before the thread owns the controller.
  const int brick_edge = controller_.loop().volume().brick_edge();
  thread_ = std::thread([this, warm_heap_bytes, brick_edge] {
    name_this_thread("sculpting");
    if (warm_heap_bytes > 0) {
      warm_this_threads_heap(warm_heap_bytes);
      core::keep_stroke_buffers(brick_edge, kWarmStrokeBricks);
    }
    std::unique_lock gate(gate_);
    warmed_ = true;
    gate_changed_.notify_all();
    gate_changed_.wait(gate, [this] { return go_ || stop_.load(std::memory_order_relaxed); });
    gate.unlock();
    run();
  });
  std::unique_lock gate(gate_);
  gate_changed_.wait(gate, [this] { return warmed_; });
}

void InputHub::start() {
  prepare(0);
  std::lock_guard gate(gate_);
  go_ = true;
  gate_changed_.notify_all();
}

void InputHub::stop() {
  {
    std::lock_guard gate(gate_);
    stop_.store(true, std::memory_order_relaxed);
    gate_changed_.notify_all();
  }
  if (thread_.joinable()) thread_.join();
}

std::unique_lock<PriorityInheritingMutex> InputHub::frame_turn(bool must) {
  std::unique_lock turn(mutex_, std::defer_lock);
  if (must) {
    turn.lock();
    return turn;
  }
  constexpr int64_t kPatienceNs = 1'000'000;
  const int64_t start = hal::monotonic_ns();
  while (!turn.try_lock() && hal::monotonic_ns() - start <= kPatienceNs)
    std::this_thread::yield();
  return turn;
}

void InputHub::release_held(int64_t now) {
  if (held_events_.empty() && held_commands_.empty()) return;
  hal::InputFrame held;
  held.events.swap(held_events_);
  controller_.device_frame(held, now, held_commands_);
  held_commands_.clear();
}

void InputHub::poll_now(bool land) {
  poll(hal::monotonic_ns(), land);
}

void InputHub::note_devices() {
  const std::optional<uint32_t> id = registry_->first_device();
  if (!id) return;
  controller_.set_device(registry_->reader(*id)->info(), normalizer_text_);
  device_id_ = *id;
}

void InputHub::run() {
  const int64_t started_ns = hal::monotonic_ns();
  const int64_t faults_at_start = this_threads_page_faults();
  const Doorbell& doorbell = registry_->doorbell();
  int64_t due_ns = started_ns;  // the next poll of the 1 kHz clock
  bool rang = false;            // this poll was woken by a reader
  int64_t poll_started_ns = started_ns;
  while (!stop_.load(std::memory_order_relaxed)) {
    // Read before polling: a report pushed while this poll runs makes the
    // wait below return at once.
    const uint32_t rings = doorbell.rings();
    const int64_t before_lock = hal::monotonic_ns();
    {
      std::lock_guard lock(mutex_);
      const int64_t now = hal::monotonic_ns();
      // A session played as a device starts once the window's opening
      // surface is meshed (sim_backend.h), as a sculptor starts once the
      // sculpture is on screen, and at the latest after kSessionStartWaitNs.
      // (Under the lock: the render thread gives the levels.)
      if (sim_ != nullptr && !session_started_ &&
          ((!levels_.empty() && mesher_.meshed()) || now - started_ns > kSessionStartWaitNs)) {
        sim_->start_playing();
        session_started_ = true;
      }
      const double waited_ms = static_cast<double>(now - before_lock) * 1e-6;
      figures_.waits.sum_ms += waited_ms;
      figures_.waits.max_ms = std::max(figures_.waits.max_ms, waited_ms);
      if (waited_ms > 1.0) ++figures_.waits.over_1ms;
      if (rang) ++figures_.polls_on_reports;
      poll_started_ns = now;
      poll(now);
      figures_.sculpt_ms += static_cast<double>(hal::monotonic_ns() - now) * 1e-6;
      figures_.page_faults = this_threads_page_faults() - faults_at_start;
    }
    // The clock's polls keep absolute deadlines: a slow poll (a big dab) is
    // followed by the next at once, not a millisecond later. Between them
    // the thread sleeps until a device's reader rings: a report is sculpted
    // as it comes, where it waited for the next poll, half a millisecond
    // on average (a played session's latencies did not count that wait).
    const int64_t now = hal::monotonic_ns();
    rang = false;
    if (now >= due_ns) {
      due_ns += kPollIntervalNs;
      if (now > due_ns) {
        due_ns = now;  // behind: do not try to catch up with the polls missed
        continue;
      }
    }
    rang = doorbell.wait_until(rings, due_ns);
    // A device that floods (a tracker sending 10,000 datagrams a second)
    // gets a poll every kMinPollSpacingNs, its reports taken together, not
    // one poll each.
    if (rang) hal::sleep_until_ns(poll_started_ns + kMinPollSpacingNs);
  }
}

void InputHub::poll(int64_t now, bool land) {
  ++figures_.polls;
  if (now - last_scan_ns_ > kScanIntervalNs) {
    if (!registry_->scan().opened.empty()) note_devices();
    last_scan_ns_ = now;
  }
  // Checked before polling: once true, this poll gets the session's last reports.
  const bool session_played = sim_ != nullptr && sim_->played();
  input_.clear();
  registry_->poll(input_, now);
  // A recorded unplug is not the end: the device comes back at the next
  // scan and plays on, as `sculpt replay` does (sim_backend.h).
  const bool done = session_played;
  // A sim device hands over a command before it reads the report after it,
  // so once the reports are polled, every command older than the newest of
  // them is here; younger ones wait for the reports before them (poll
  // timing must not change where a command falls among the reports).
  std::vector<std::pair<int64_t, sim::Command>> commands;
  if (sim_ != nullptr) {
    for (auto& c : sim_->take_commands())
      pending_commands_.push_back(std::move(c));
    for (const hal::InputEvent& e : input_.events) {
      if (e.kind == hal::InputKind::kMotion || e.kind == hal::InputKind::kButton)
        newest_report_t_ns_ = std::max(newest_report_t_ns_, e.t_ns);  // the device's clock
    }
    const bool device_gone = registry_->open_count() == 0 || session_played;
    auto ready = std::stable_partition(
        pending_commands_.begin(), pending_commands_.end(),
        [&](const auto& c) { return device_gone || c.first <= newest_report_t_ns_; });
    commands.assign(pending_commands_.begin(), ready);
    pending_commands_.erase(pending_commands_.begin(), ready);
  }
  // An offset or closing computing on its worker (seconds on a big
  // sculpture): later reports and commands are held until it lands, so they
  // sculpt what it leaves, as its replay does, while the frame keeps its turn
  // to steer and draw. The session's end and the last poll wait for it.
  // Held input is bounded: past kMaxHeldEvents (a minute of a 1 kHz
  // tracker) the hub waits for the result instead of holding more.
  const bool must_land = done || land || held_events_.size() >= kMaxHeldEvents;
  if (!controller_.land_morphology(must_land)) {
    held_events_.insert(held_events_.end(), input_.events.begin(), input_.events.end());
    figures_.held_events += static_cast<int64_t>(input_.events.size());
    held_commands_.insert(held_commands_.end(), commands.begin(), commands.end());
  } else {
    release_held(now);
    controller_.device_frame(input_, now, commands);
    controller_.loop().catch_up_brush_preview(hal::monotonic_ns());
  }
  if (const hal::DeviceReader* reader = registry_->reader(device_id_); reader != nullptr)
    controller_.reader_samples(reader->counters().motion_samples, now);
  if (listener_ != nullptr) listener_->on_poll(controller_, now);
  // What was sculpted goes to the mesher at once; before the render thread
  // has said which levels it draws, there is nothing to mesh for.
  core::StoredVoxelsByBrick stored = controller_.loop().take_stored_voxels();
  if (!levels_.empty()) {
    const core::Volume& volume = controller_.loop().volume();
    if (static_cast<int64_t>(levels_.size()) == volume.brick_count()) {
      // Handed over when queued, not when submit() returns (see there).
      int64_t queued_ns = -1;
      const uint64_t change = mesher_.submit(volume, controller_.loop().volume_generation(),
                                             levels_, &queued_ns, std::move(stored));
      controller_.surface_submitted(change, queued_ns >= 0 ? queued_ns : hal::monotonic_ns());
    }
  }
  // Recording and autosave keep the frame's pace: a file write a millisecond
  // would be mostly system calls.
  if (now - last_tick_ns_ >= kTickIntervalNs) {
    controller_.tick(hal::monotonic_ns());
    last_tick_ns_ = now;
  }
  if (done) replay_done_.store(true, std::memory_order_release);
}

}  // namespace sculpt::station
