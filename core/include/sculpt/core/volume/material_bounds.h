#pragma once
// Where the material is: the box around every voxel with any density, as
// "frame selected" and "the sculpture becomes the tool" need it.

#include <optional>

#include "sculpt/core/grid/box.h"
#include "sculpt/core/volume/volume.h"

namespace sculpt::core {

/// The smallest box holding every voxel of density above 0; nothing when
/// the volume is empty. Uniform bricks count whole without decoding, and a
/// detailed brick is decoded only when it could widen the box found so far,
/// so a block of clay costs its surface, not its volume.
std::optional<Box> material_bounds(const Volume& volume);

}  // namespace sculpt::core
