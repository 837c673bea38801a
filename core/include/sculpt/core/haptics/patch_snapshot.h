#pragma once
// What the haptic tick reads: a dense cube of signed distances around the tool
// (DESIGN.md §5a), built by DistancePatch on the sculpting side and handed to
// the tick through PatchExchange.
//
// Values are in voxel units, negative inside, sampled at the material's voxel
// centres: value (i, j, k) is the distance at voxel origin + (i, j, k). They
// are accurate (0.1 voxel) where |phi| <= band_vox; beyond, a voxel holds an
// estimate or, far from any surface, the bound +-clamp_vox, which never
// exceeds the true distance, so a step of phi - r stays safe anywhere.
//
// Sampling is trilinear and never allocates, locks or decodes: it is the only
// thing the 1 kHz tick does with the material.

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

namespace sculpt::core {

/// The field and its gradient at a point (voxel units; the gradient is
/// unit-free, about 1 long near the surface).
struct FieldSample {
  float phi_vox = 0.0f;
  glm::vec3 gradient{0.0f};
};

struct PatchSnapshot {
  /// Material voxel of value (0, 0, 0).
  glm::ivec3 origin{0};
  /// Values per axis (a cube).
  int edge = 0;
  /// Half width of the accurate band, and the value of voxels far from any
  /// surface (a lower bound of their distance).
  float band_vox = 0.0f;
  float clamp_vox = 0.0f;
  /// Increments each time the sculpting side changes the values.
  uint64_t version = 0;
  /// edge^3 values, x fastest.
  std::vector<float> phi;

  bool empty() const { return edge == 0; }
  /// Trilinear value at p, and the gradient blended trilinearly from central
  /// differences at the cell's corners. Points outside the
  /// patch are clamped onto its boundary (the proxy never steps past it).
  FieldSample sample(glm::vec3 p) const;
  /// The value stored at material voxel v (which must lie in the patch).
  float at(glm::ivec3 v) const;
};

}  // namespace sculpt::core
