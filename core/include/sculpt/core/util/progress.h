#pragma once
// One progress and cancel callback for long core work (distance fields,
// voxelize, closing, whole-volume meshing), in the manner of OpenVDB's
// interrupter: the work reports a fraction done in [0, 1] and polls
// cancelled(); the callback returns false to cancel. A cancelled call
// returns early with an unspecified result: the caller checks
// `progress->cancelled()` (or status()) and discards it. With no Progress
// (nullptr) the work runs as before, to the same bytes; with one that never
// cancels, also to the same bytes.
//
// Thread safety: report(), cancelled() and ProgressStage::step() may be
// called from parallel_for workers at once. The callback is called by one
// thread at a time, with fractions that never decrease, at most about once
// per thousandth of the work (and always for the first report), so it may
// be slow-ish (a terminal write) without slowing the work.

#include <atomic>
#include <cstdint>
#include <functional>
#include <mutex>

#include "sculpt/base/result.h"

namespace sculpt::core {

class Progress {
 public:
  /// Called with the fraction done (0..1); returns false to cancel.
  using Callback = std::function<bool(double fraction)>;

  Progress() = default;
  explicit Progress(Callback callback) : callback_(std::move(callback)) {}
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  /// Reports `fraction` done (clamped to [0, 1]); calls the callback when it
  /// has advanced enough since the last call. Returns !cancelled().
  bool report(double fraction);
  /// Cancels from outside the callback (tests, a second thread).
  void cancel() { cancelled_.store(true, std::memory_order_relaxed); }
  bool cancelled() const { return cancelled_.load(std::memory_order_relaxed); }
  /// Error "cancelled" once cancelled, else success.
  Status status() const;

 private:
  Callback callback_;
  std::atomic<bool> cancelled_{false};
  std::mutex mutex_;
  double last_ = -1.0;  // last fraction passed to the callback (guarded)
};

/// True when `progress` is set and cancelled: the check after each stage.
inline bool cancelled(const Progress* progress) {
  return progress != nullptr && progress->cancelled();
}

/// A part [begin, end] of a parent's fraction as a Progress of its own, for
/// handing one call of a longer job (the two distance fields of a closing)
/// a Progress that reports 0..1. Null when the parent is null. Cancelling the
/// parent cancels this one at its next report.
class SubProgress {
 public:
  SubProgress(Progress* parent, double begin, double end);
  Progress* get() { return parent_ != nullptr ? &progress_ : nullptr; }

 private:
  Progress* parent_;
  Progress progress_;
};

/// A stage of a Progress: the span [begin, end) of its fraction, counted in
/// `total` units of work (slices, bricks, triangles). Safe to step from
/// several threads. With a null Progress every call is a no-op.
class ProgressStage {
 public:
  ProgressStage(Progress* progress, double begin, double end, int64_t total)
      : progress_(progress), begin_(begin), end_(end), total_(total > 0 ? total : 1) {}

  /// Marks `units` more done. Returns false once cancelled.
  bool step(int64_t units = 1) {
    if (progress_ == nullptr) return true;
    const int64_t done = done_.fetch_add(units, std::memory_order_relaxed) + units;
    const double f = double(done < total_ ? done : total_) / double(total_);
    return progress_->report(begin_ + (end_ - begin_) * f);
  }
  bool cancelled() const { return core::cancelled(progress_); }
  Progress* progress() const { return progress_; }

 private:
  Progress* progress_;
  double begin_, end_;
  int64_t total_;
  std::atomic<int64_t> done_{0};
};

/// parallel_for (parallel_for.h) that steps `stage` once per index and skips
/// the remaining indices once the stage's Progress is cancelled.
void parallel_for(int64_t count, const std::function<void(int64_t)>& body, int threads,
                  ProgressStage& stage);

}  // namespace sculpt::core
