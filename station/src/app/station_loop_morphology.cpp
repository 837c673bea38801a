// StationLoop: offset and closing of the sculpture (Jones & Satherley §4.2),
// the same code as `sculpt offset` and `sculpt close`, as one undo step.

#include <algorithm>
#include <atomic>
#include <cmath>
#include <thread>

#include "app/morphology_job.h"
#include "sculpt/base/thread_times.h"
#include "sculpt/core/distance/distance_io.h"
#include "sculpt/core/distance/iso_triangulation.h"
#include "sculpt/core/distance/morphology.h"
#include "sculpt/core/volume/material_bounds.h"
#include "sculpt/sim/session/command_limits.h"
#include "sculpt/station/app/station_loop.h"

namespace sculpt::station {

StationLoop::~StationLoop() = default;
StationLoop::StationLoop(StationLoop&&) noexcept = default;
StationLoop& StationLoop::operator=(StationLoop&&) noexcept = default;

void StationLoop::morphology(const sim::Command& c) {
  morphology_ = {};
  if (pressed_) release();
  const bool close = c.choice == sim::kMorphologyClose;
  const float by = std::clamp(std::isfinite(c.values[0]) ? c.values[0] : 0.0f,
                              -sim::kMaxMorphologyVox, sim::kMaxMorphologyVox);
  if (close && !(by > 0.0f)) return;
  const std::optional<core::Box> bounds = core::material_bounds(*volume_);
  if (!bounds) return;
  // Only the material and what the surface can reach changes: the surface
  // moves at most |by| voxels (a closing's dilation reaches `by` out), plus
  // the density ramp's 2 voxels. Distances inside the box are exact, as
  // every surface voxel lies in it.
  const int reach = static_cast<int>(std::ceil(std::abs(by))) + 3;
  auto job = std::make_unique<MorphologyJob>();
  job->box = core::intersect(core::Box{bounds->lo - reach, bounds->hi + reach},
                             core::Box{glm::ivec3(0), volume_->dims()});
  job->close = close;
  job->by = by;
  job->phi = core::level_function(volume_->read(job->box));
  for (size_t i = 0; i < job->phi.size(); ++i)
    job->inside_before += job->phi[i] < 0.0f;
  // A block solid throughout the box has no surface to move.
  if (job->inside_before == 0 || job->inside_before == static_cast<int64_t>(job->phi.size()))
    return;
  if (!options_.background_morphology) {
    job->compute();
    land(*job);
    return;
  }
  // The volume stays as it is until the job lands: every later input
  // settles first (handle()), so it sculpts what the job leaves.
  MorphologyJob* computing = job.get();
  job->worker = std::thread([computing] {
    name_this_thread("morphology");
    computing->compute();
  });
  morphology_job_ = std::move(job);
}

bool StationLoop::morphology_ready() const {
  return morphology_job_ != nullptr && morphology_job_->done.load(std::memory_order_acquire);
}

void StationLoop::settle() {
  if (!morphology_job_) return;
  std::unique_ptr<MorphologyJob> job = std::move(morphology_job_);
  if (job->worker.joinable()) job->worker.join();
  land(*job);
}

void StationLoop::land(MorphologyJob& job) {
  sculptor_->external_edit(job.box, [&] { volume_->write(job.box.lo, job.density); });
  morphology_.applied = true;
  morphology_.inside_before = job.inside_before;
  morphology_.inside_after = job.inside_after;
}

}  // namespace sculpt::station
