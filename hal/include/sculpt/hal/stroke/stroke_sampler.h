#pragma once
// Places dabs along the tool path by arc length (DESIGN.md §5): one dab at the
// start of a stroke, then one every `spacing` along the polyline of poses,
// with orientation slerped and time interpolated between the two poses that
// bracket it. The dab pattern depends on the path, not on how densely the
// device sampled it.

#include <cstdint>
#include <vector>

#include "sculpt/hal/pose/tool_pose.h"

namespace sculpt::hal {

struct Dab {
  glm::vec3 position{0.0f};  ///< world units
  glm::quat orientation{1.0f, 0.0f, 0.0f, 0.0f};
  int64_t t_ns = 0;
  int64_t index = 0;  ///< 0 for the stroke's first dab
};

class StrokeSampler {
 public:
  /// tool_size: the tool's diameter in world units (> 0); spacing_fraction:
  /// dab spacing as a fraction of it (> 0; 0.25 overlaps dabs 4x).
  explicit StrokeSampler(float tool_size, float spacing_fraction = 0.25f);

  /// Starts a stroke at `pose` and appends its first dab.
  void begin(const ToolPose& pose, std::vector<Dab>& out);
  /// Extends the stroke to `pose`, appending every dab the new segment passes.
  /// Without an open stroke it does nothing.
  void add(const ToolPose& pose, std::vector<Dab>& out);
  /// Closes the stroke (the device was released or vanished). Appends nothing:
  /// the partial spacing is dropped so that where a stroke stops does not
  /// depend on when the last report came.
  void end();

  bool active() const { return active_; }
  float spacing() const { return spacing_; }
  /// Path length of the open stroke, world units.
  double length() const { return length_; }

 private:
  float spacing_;
  bool active_ = false;
  ToolPose last_;
  double length_ = 0.0;
  double next_at_ = 0.0;  // arc length of the next dab
  int64_t next_index_ = 0;
};

}  // namespace sculpt::hal
