#include "sculpt/station/settings/command_codec.h"

#include <cassert>
#include <cstring>

namespace sculpt::station {

sim::ToolVoxels tool_voxels_of(const core::Tool& tool) {
  sim::ToolVoxels v;
  const glm::ivec3 d = tool.density.dims();
  for (int a = 0; a < 3; ++a) {
    assert(d[a] >= 1 && d[a] <= static_cast<int>(sim::kMaxToolVoxelsEdge));
    v.dims[a] = static_cast<uint16_t>(d[a]);
    v.pivot[a] = tool.pivot[a];
  }
  v.hardness = tool.hardness;
  v.density.assign(tool.density.data(), tool.density.data() + tool.density.size());
  return v;
}

core::Tool tool_of(const sim::ToolVoxels& v) {
  core::Tool tool;
  tool.density = core::DenseGrid<uint8_t>(glm::ivec3(v.dims[0], v.dims[1], v.dims[2]));
  if (!v.density.empty())
    std::memcpy(tool.density.data(), v.density.data(),
                std::min(v.density.size(), tool.density.size()));
  tool.pivot = glm::vec3(v.pivot[0], v.pivot[1], v.pivot[2]);
  tool.hardness = v.hardness;
  return tool;
}

}  // namespace sculpt::station
