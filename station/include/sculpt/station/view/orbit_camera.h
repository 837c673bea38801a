#pragma once
// The station's camera: it orbits a target point, pans in the view plane and
// zooms along the view direction, like the camera of a CAD or sculpting
// program. GL-free (the renderer takes its matrices), so the UI's mouse and
// 3D-mouse camera control is tested without a window.
//
// Units are voxels; angles radians. Yaw turns about +Y (up), pitch tilts
// toward +Y and is kept inside (-89°, 89°) so the view never flips.

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace sculpt::core {
class Volume;
}

namespace sculpt::station {

struct Ray {
  glm::vec3 origin{0.0f};
  glm::vec3 direction{0.0f, 0.0f, -1.0f};  ///< unit
};

class OrbitCamera {
 public:
  /// Looks at the centre of the box lo..hi from the front and a little above,
  /// far enough for the whole box to fit the view.
  void frame(glm::vec3 lo, glm::vec3 hi);
  /// frame() around the volume's material ("frame selected"), or around the
  /// whole block when it is empty: a head fills a fifth of its 256^3
  /// block's view, a 512^3 bust a tenth.
  void frame_material(const core::Volume& volume);

  /// Turns the view about the target by the given angles.
  void orbit(float yaw_rad, float pitch_rad);
  /// Moves target and eye together by `pixels` of a viewport `viewport_height`
  /// pixels tall (the point under the cursor follows the cursor).
  void pan(glm::vec2 pixels, float viewport_height);
  /// Multiplies the distance to the target by `factor` (< 1 comes closer).
  void zoom(float factor);

  glm::vec3 target() const { return target_; }
  float distance() const { return distance_; }
  float yaw() const { return yaw_; }
  float pitch() const { return pitch_; }
  void set(glm::vec3 target, float yaw_rad, float pitch_rad, float distance);

  glm::vec3 eye() const;
  /// Unit vectors of the view: right, up, forward (toward the target).
  glm::vec3 right() const;
  glm::vec3 up() const;
  glm::vec3 forward() const;

  glm::mat4 view() const;
  /// Perspective projection; near and far planes follow the distance.
  glm::mat4 projection(float aspect) const;
  /// Pixels one voxel spans at a distance of one voxel, for a viewport
  /// `viewport_height` pixels high (level of detail by screen error).
  static float focal_length_px(float viewport_height);
  /// The ray through a point of the viewport, in normalised device
  /// coordinates (x, y in [-1, 1], y up).
  Ray ray(glm::vec2 ndc, float aspect) const;

  static constexpr float kFovY = 0.6981317f;  // 40 degrees

 private:
  glm::vec3 target_{128.0f};
  float yaw_ = 0.5f;
  float pitch_ = 0.35f;
  float distance_ = 600.0f;
};

}  // namespace sculpt::station
