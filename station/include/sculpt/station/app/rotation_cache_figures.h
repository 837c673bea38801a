#pragma once
// The tool rotation caches' counts as `--stats` writes them (replay and the
// window): how often a dab found its rotated tool already made.

#include <nlohmann/json.hpp>

#include "sculpt/core/tool/rotated_tool_cache.h"

namespace sculpt::station {

inline nlohmann::ordered_json rotation_cache_figures(const core::RotatedToolCacheStats& s) {
  return {{"placements", s.placements},
          {"placement_hit_rate", s.placement_hit_rate()},
          {"voxels_requested", s.voxels_requested},
          {"voxel_hit_rate", s.voxel_hit_rate()},
          {"voxels_rotated", s.voxels_rotated},
          {"evictions", s.evictions},
          {"entries", s.entries},
          {"mib", static_cast<double>(s.bytes) / (1 << 20)}};
}

}  // namespace sculpt::station
