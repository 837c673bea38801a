#include "sculpt/station/app/session_recorder.h"

#include <algorithm>

namespace sculpt::station {

Status SessionRecorder::start(const std::filesystem::path& path, const sim::SessionHeader& header,
                              const std::vector<sim::Command>& opening, int64_t now_ns) {
  if (writer_) {
    if (auto stopped = stop(); !stopped) return stopped.error();
  }
  auto writer = sim::SessionWriter::create(path, header);
  if (!writer) return writer.error();
  writer_.emplace(std::move(writer).value());
  path_ = path;
  last_t_ns_ = now_ns;
  // Those applied before the opening are in the sculpture it starts from.
  take_released(nullptr);
  pending_.clear();
  for (const sim::Command& c : opening)
    command(c, now_ns);
  return flush();
}

void SessionRecorder::command(const sim::Command& c, int64_t t_ns) {
  if (writer_) pending_.push_back(sim::SessionRecord::of(t_ns, c));
}

void SessionRecorder::raw(const hal::RawEvent& e) {
  std::lock_guard lock(raw_mutex_);
  raw_.push_back(e);
}

void SessionRecorder::release_until(int64_t t_ns) {
  released_t_ns_ = t_ns;
  if (!writer_) take_released(nullptr);
}

void SessionRecorder::take_released(std::vector<hal::RawEvent>* into) {
  std::lock_guard lock(raw_mutex_);
  // Events are tapped in time order: the released ones are a prefix.
  const auto held = std::find_if(raw_.begin(), raw_.end(),
                                 [&](const hal::RawEvent& e) { return e.t_ns > released_t_ns_; });
  if (into != nullptr) into->assign(raw_.begin(), held);
  raw_.erase(raw_.begin(), held);
}

Status SessionRecorder::flush() {
  if (!writer_) return {};
  std::vector<hal::RawEvent> raw;
  take_released(&raw);
  // Commands first, so a command and a report of the same time keep the order
  // the station saw them in; then a stable merge by time. A report that took
  // longer through its queue than a command issued after it is written at
  // the command's time (times never go back in a session file).
  std::vector<sim::SessionRecord> batch = std::move(pending_);
  pending_.clear();
  for (const hal::RawEvent& e : raw)
    batch.push_back(sim::SessionRecord::of(e));
  std::stable_sort(
      batch.begin(), batch.end(),
      [](const sim::SessionRecord& a, const sim::SessionRecord& b) { return a.t_ns() < b.t_ns(); });
  for (sim::SessionRecord& r : batch) {
    if (r.t_ns() < last_t_ns_) {
      if (r.kind == sim::SessionRecord::Kind::kEvent) {
        r.event.t_ns = last_t_ns_;
      } else {
        r.command_t_ns = last_t_ns_;
      }
    }
    last_t_ns_ = r.t_ns();
    if (Status st = writer_->append(r); !st) {
      writer_.reset();
      return st;
    }
  }
  Status st = writer_->sync_if_due();
  if (!st) writer_.reset();
  return st;
}

Result<int64_t> SessionRecorder::stop() {
  if (!writer_) return int64_t{0};
  if (Status st = flush(); !st) return st.error();
  const int64_t records = writer_->records();
  Status st = writer_->close();
  writer_.reset();
  if (!st) return st.error();
  return records;
}

}  // namespace sculpt::station
