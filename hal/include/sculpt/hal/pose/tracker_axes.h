#pragma once
// A tracker's axes named the way a user reads them off the tracker's manual:
// "x,z,-y" says the sculpture's x is the tracker's x, its y the tracker's z
// and its z the tracker's -y (DESIGN.md §3's frame: x right, y up, z towards
// the viewer). The result is hal::TrackerCalibration::tracker_to_sculpture.

#include <string_view>

#include <glm/gtc/quaternion.hpp>

#include "sculpt/base/result.h"

namespace sculpt::hal {

/// The rotation the spec names, or why it names none: three comma-separated
/// axes from x, y, z (each once, a leading '-' to flip it) that keep the
/// hand's handedness. A spec that swaps two axes without flipping one is a
/// mirror image, which no rotation is: the error says which sign to flip.
Result<glm::dquat> parse_tracker_axes(std::string_view spec);

}  // namespace sculpt::hal
