// StationLoop: offset and closing of the sculpture (Jones & Satherley §4.2),
// the same code as `sculpt offset` and `sculpt close`, as one undo step.

#include <algorithm>
#include <cmath>

#include "sculpt/core/distance/distance_io.h"
#include "sculpt/core/distance/iso_triangulation.h"
#include "sculpt/core/distance/morphology.h"
#include "sculpt/core/volume/material_bounds.h"
#include "sculpt/sim/session/command_limits.h"
#include "sculpt/station/app/station_loop.h"

namespace sculpt::station {

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
  const core::Box box = core::intersect(core::Box{bounds->lo - reach, bounds->hi + reach},
                                        core::Box{glm::ivec3(0), volume_->dims()});
  const core::DenseGrid<float> phi = core::level_function(volume_->read(box));
  int64_t inside = 0;
  for (size_t i = 0; i < phi.size(); ++i)
    inside += phi[i] < 0.0f;
  // A block solid throughout the box has no surface to move.
  if (inside == 0 || inside == static_cast<int64_t>(phi.size())) return;
  // The distance transforms' result does not depend on the thread count,
  // so a replay on another machine makes the same voxels.
  const core::DenseGrid<float> moved = close
                                           ? core::close_distance(phi, by)
                                           : core::offset_distance(core::surface_distance(phi), by);
  const core::DenseGrid<uint8_t> density = core::density_from_distance_field(moved);
  sculptor_->external_edit(box, [&] { volume_->write(box.lo, density); });
  morphology_.applied = true;
  morphology_.inside_before = inside;
  for (size_t i = 0; i < moved.size(); ++i)
    morphology_.inside_after += moved[i] < 0.0f;
}

}  // namespace sculpt::station
