// Grab as a warp sampled backwards: each voxel reads where its material
// comes from, so the material is neither duplicated nor torn, which a
// forward copy (write each voxel's material where it goes) could not
// promise on a grid. Why in steps: the single warp x - w(x) D folds once
// |D| times the falloff's slope reaches 1 (a drag longer than the falloff's
// width), tearing the material; moving the ball along in steps that each
// stay well within that bound keeps the warp invertible for any drag, and
// keeps the dragged material under the ball's centre, where it moves
// rigidly (the volume kept: the "physical behaviour" the discrete-tools
// paper leaves as future work).

#include "sculpt/core/sculpt/grab_brush.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <vector>

#include <glm/geometric.hpp>

#include "brush_field.h"

namespace sculpt::core {
namespace {

// Fixed-point rounds per step: each step contracts the error by 1/2 or more.
constexpr int kInverseRounds = 12;
// Most steps: each voxel costs steps x rounds falloff evaluations, and a
// drag needing more (over 170 voxels with a hard ball) is not one gesture.
constexpr int kMaxSteps = 256;

}  // namespace

Status check_grab_brush(const GrabBrushOptions& o) {
  return brush::check_ball({o.radius_vox, o.hardness, o.strength});
}

int64_t grab_stroke(Volume& volume, Sculptor& sculptor, std::span<const StrokeSample> path,
                    const GrabBrushOptions& o) {
  assert(!path.empty() && check_grab_brush(o));
  const glm::vec3 start = path.front().position_vox;
  const glm::vec3 displacement = path.back().position_vox - start;
  const float length = glm::length(displacement);
  if (length <= 0.0f || o.strength <= 0.0f) return 0;
  const brush::Ball ball{o.radius_vox, o.hardness, o.strength};
  const StrokeSample ends[2] = {path.front(), path.back()};
  const Box region = brush::reach_box(volume, ends, ball);
  if (region.empty()) return 0;
  const brush::Field before(volume, region, 2);
  // tool_density()'s taper: a smoothstep (slope at most 1.5 over its width)
  // over 2 + (1 - hardness)(radius - 1) voxels.
  const float taper = 2.0f + (1.0f - o.hardness) * std::max(0.0f, o.radius_vox - 1.0f);
  const float slope = o.strength * 1.5f / taper;
  const int steps =
      std::clamp(static_cast<int>(std::ceil(std::min(length * slope / 0.5f, 1e6f))), 1, kMaxSteps);
  const glm::vec3 step = displacement / static_cast<float>(steps);
  return brush::write(volume, sculptor, before, region, ends, ball,
                      [&](glm::ivec3 v, float, const brush::PathDistance&) {
                        // Undo the steps from the last: y_k = x - w(|y_k - c_k|) step.
                        glm::vec3 x(v);
                        for (int k = steps - 1; k >= 0; --k) {
                          const glm::vec3 centre = start + static_cast<float>(k) * step;
                          glm::vec3 y = x - ball.weight(glm::length(x - centre)) * step;
                          for (int r = 0; r < kInverseRounds; ++r)
                            y = x - ball.weight(glm::length(y - centre)) * step;
                          x = y;
                        }
                        return x == glm::vec3(v) ? before.at(v) : before.sample(x);
                      });
}

}  // namespace sculpt::core
