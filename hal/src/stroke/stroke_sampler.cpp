#include "sculpt/hal/stroke/stroke_sampler.h"

#include <cassert>
#include <cmath>

#include <glm/geometric.hpp>

namespace sculpt::hal {

StrokeSampler::StrokeSampler(float tool_size, float spacing_fraction)
    : spacing_(tool_size * spacing_fraction) {
  assert(tool_size > 0.0f && spacing_fraction > 0.0f);
}

void StrokeSampler::begin(const ToolPose& pose, std::vector<Dab>& out) {
  active_ = true;
  last_ = pose;
  length_ = 0.0;
  next_index_ = 0;
  out.push_back(Dab{pose.position, pose.orientation, pose.t_ns, next_index_++});
  next_at_ = spacing_;
}

void StrokeSampler::add(const ToolPose& pose, std::vector<Dab>& out) {
  if (!active_) return;
  // Lengths in double: a long stroke of short segments must not drift.
  const glm::dvec3 a(last_.position), b(pose.position);
  const double seg = glm::length(b - a);
  const double end = length_ + seg;
  while (seg > 0.0 && next_at_ <= end) {
    const double u = (next_at_ - length_) / seg;
    Dab d;
    d.position = glm::vec3(a + (b - a) * u);
    d.orientation =
        glm::normalize(glm::slerp(last_.orientation, pose.orientation, static_cast<float>(u)));
    d.t_ns = last_.t_ns +
             static_cast<int64_t>(std::llround(static_cast<double>(pose.t_ns - last_.t_ns) * u));
    d.index = next_index_++;
    out.push_back(d);
    next_at_ += spacing_;
  }
  length_ = end;
  last_ = pose;
}

void StrokeSampler::end() {
  active_ = false;
}

}  // namespace sculpt::hal
