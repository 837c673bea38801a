#include "sculpt/core/util/progress.h"

#include <algorithm>

#include "sculpt/core/util/parallel_for.h"

namespace sculpt::core {
namespace {

// The callback sees at most about this many calls per run: a terminal bar
// needs no more, and workers reporting every slice of a 1024^3 volume must
// not queue on the mutex.
constexpr double kMinStep = 0.001;

}  // namespace

bool Progress::report(double fraction) {
  if (cancelled()) return false;
  if (!callback_) return true;
  fraction = std::clamp(fraction, 0.0, 1.0);
  // A worker that finds another one in the callback skips its report: the
  // next one carries a fraction at least as large.
  std::unique_lock<std::mutex> lock(mutex_, std::try_to_lock);
  if (!lock.owns_lock()) return !cancelled();
  const bool first = last_ < 0.0;
  if (!first && fraction < last_ + kMinStep && !(fraction == 1.0 && last_ < 1.0))
    return !cancelled();
  if (!first && fraction <= last_) return !cancelled();
  last_ = fraction;
  if (!callback_(fraction)) cancel();
  return !cancelled();
}

Status Progress::status() const {
  if (cancelled()) return Error("cancelled");
  return {};
}

SubProgress::SubProgress(Progress* parent, double begin, double end)
    : parent_(parent), progress_([parent, begin, end](double f) {
        // The end exactly: the last report of a part must not fall a rounding
        // error short of it (and be skipped as too small a step).
        return parent == nullptr || parent->report(f >= 1.0 ? end : begin + (end - begin) * f);
      }) {}

void parallel_for(int64_t count, const std::function<void(int64_t)>& body, int threads,
                  ProgressStage& stage) {
  if (stage.progress() == nullptr) {
    parallel_for(count, body, threads);
    return;
  }
  parallel_for(
      count,
      [&](int64_t i) {
        if (stage.cancelled()) return;
        body(i);
        stage.step();
      },
      threads);
}

}  // namespace sculpt::core
