#include "sculpt/station/app/dab_stand_ins.h"

#include <glm/gtc/matrix_transform.hpp>

#include "sculpt/hal/types/clock.h"
#include "sculpt/station/view/tool_outline.h"

namespace sculpt::station {

DabStandIns::ToolMesh DabStandIns::ToolMesh::of(const core::Tool& tool, uint64_t version) {
  return {version, std::make_shared<const core::Mesh>(stand_in_outline(tool)),
          std::make_shared<const core::Mesh>(stand_in_outline(tool, /*coarse=*/true)), tool.pivot};
}

glm::mat4 stand_in_model(const DabStandIn& s, glm::vec3 pivot, bool reflected) {
  // The pivot goes to the dab's position, turned by its orientation.
  const glm::mat4 placed = glm::translate(glm::mat4(1.0f), s.position) *
                           glm::mat4_cast(s.orientation) * glm::translate(glm::mat4(1.0f), -pivot);
  if (!reflected || !s.mirror) return placed;
  // The sculptor's mirror dab is the world's reflection of this one across
  // the plane x[axis] = centre (Sculptor::dab()): x -> 2 centre - x.
  glm::mat4 reflect(1.0f);
  const int a = s.mirror->axis;
  reflect[a][a] = -1.0f;
  reflect[3][a] = 2.0f * s.mirror->centre_vox;
  return reflect * placed;
}

int64_t DabStandIns::add(std::span<const hal::Dab> dabs, uint64_t tool_version,
                         std::optional<core::MirrorPlane> mirror, bool carves) {
  std::lock_guard lock(mutex_);
  for (const hal::Dab& d : dabs) {
    DabStandIn& s = kept_.emplace_back();
    s.position = d.position;
    s.orientation = d.orientation;
    s.mirror = mirror;
    s.tool_version = tool_version;
    s.carves = carves;
  }
  if (kept_.size() > kMaxKept) {
    const size_t over = kept_.size() - kMaxKept;
    kept_.erase(kept_.begin(), kept_.begin() + static_cast<std::ptrdiff_t>(over));
    dropped_ += static_cast<int64_t>(over);
  }
  return hal::monotonic_ns();
}

void DabStandIns::handed_over(uint64_t change) {
  std::lock_guard lock(mutex_);
  for (auto it = kept_.rbegin(); it != kept_.rend() && it->change == 0; ++it)
    it->change = change;
}

std::vector<DabStandIn> DabStandIns::showing(uint64_t meshed_change) {
  std::lock_guard lock(mutex_);
  std::erase_if(kept_,
                [&](const DabStandIn& s) { return s.change != 0 && s.change <= meshed_change; });
  return kept_;
}

void DabStandIns::set_tool(ToolMesh tool) {
  std::lock_guard lock(mutex_);
  tool_ = std::move(tool);
}

DabStandIns::ToolMesh DabStandIns::tool() const {
  std::lock_guard lock(mutex_);
  return tool_;
}

size_t DabStandIns::kept() const {
  std::lock_guard lock(mutex_);
  return kept_.size();
}

int64_t DabStandIns::dropped() const {
  std::lock_guard lock(mutex_);
  return dropped_;
}

}  // namespace sculpt::station
