#pragma once
// Tool-shaped contact with force and torque: the tool's point shell
// (point_shell.h) against the material's distance patch, coupled to the
// device by a six-degree-of-freedom virtual coupling (McNeely, Puterbaugh &
// Troy 1999), solved quasi-statically each tick (Wan & McNeely 2003): the
// proxy pose is moved, a few bounded steps a tick, to where the coupling
// spring's pull balances the penalty forces of the shell points inside the
// material. The device feels the coupling: the force K (proxy - device) and
// the torque K_r times the rotation from device to proxy. A 3-DOF device
// takes the force only.
//
// Units: positions in material voxels; K in N/mm with voxel_mm; K_r in N·mm
// per radian, by default K times the tool's reach squared (the spring as if
// it pulled at the tool's rim); force N, torque N·m. The tick reads only the
// patch and never allocates.

#include <cstdint>
#include <vector>

#include <glm/gtc/quaternion.hpp>
#include <glm/vec3.hpp>

#include "sculpt/core/haptics/patch_snapshot.h"
#include "sculpt/core/haptics/point_shell.h"

namespace sculpt::core {

struct ToolProxyOptions {
  float stiffness_n_per_mm = 1.0f;
  float voxel_mm = 0.5f;
  /// Rotational stiffness, N·mm/rad; 0: stiffness times the reach squared.
  float rotational_stiffness_nmm_per_rad = 0.0f;
  float max_force_n = 8.0f;
  float max_torque_nm = 0.5f;
  /// Quasi-static steps a tick, and the longest move and turn of one.
  int steps = 4;
  float max_step_vox = 0.25f;
  float max_turn_rad = 0.05f;
};

struct ToolTick {
  glm::vec3 position_vox{0.0f};
  glm::quat orientation{1.0f, 0.0f, 0.0f, 0.0f};
  glm::vec3 force_n{0.0f};
  glm::vec3 torque_nm{0.0f};
  /// Shell points inside the material after the tick.
  int points_in_contact = 0;
  bool contact = false;
};

class ToolProxy {
 public:
  ToolProxy(PointShell shell, const ToolProxyOptions& options = {});

  /// Places the proxy at the device's pose.
  void reset(glm::vec3 position_vox, glm::quat orientation);
  /// One tick with the device at this pose.
  const ToolTick& update(const PatchSnapshot& field, glm::vec3 device_vox, glm::quat device);

  const PointShell& shell() const { return shell_; }
  const ToolTick& state() const { return state_; }

 private:
  struct Wrench {
    glm::vec3 force{0.0f};    // N
    glm::vec3 torque{0.0f};   // N·voxel
    float stiffness = 0.0f;   // N/voxel summed over the points in contact
    float rotational = 0.0f;  // N·voxel/rad summed likewise
    int points = 0;
    float clearance = 1e30f;  // least distance of a point to the material, voxels (lower bound)
  };
  Wrench contact_wrench(const PatchSnapshot& field, glm::vec3 position, glm::quat orientation);

  PointShell shell_;
  ToolProxyOptions options_;
  float k_n_per_vox_;
  float kr_n_vox_per_rad_;
  ToolTick state_;
  bool placed_ = false;
  // The shell one array per axis, and the tick's scratch (sized once).
  std::vector<float> px_, py_, pz_, wx_, wy_, wz_;
  std::vector<int32_t> nearest_;
};

}  // namespace sculpt::core
