#pragma once
// The controller tests' station: a 64^3 block with a slab of clay 12 voxels
// in from every side (its top face at 51), its files in a scratch folder.

#include "scratch_dir.h"
#include "sculpt/station/app/station_controller.h"

namespace sculpt::station::test_blocks {

inline ControllerOptions small_block(const test::ScratchDir& dir) {
  ControllerOptions o;
  o.loop.volume_dims = glm::ivec3(64);
  o.loop.clay_margin = 12;
  o.project = dir.path() / "p.sculpt";
  o.mesh_export = dir.path() / "m.ply";
  o.recording = dir.path() / "r.scs";
  o.autosave_seconds = 1.0;
  o.normalizer_config_path = (dir.path() / "cfg" / "input.conf").string();
  return o;
}

}  // namespace sculpt::station::test_blocks
