#include "sculpt/hal/pose/tracker_axes.h"

#include <array>
#include <string>

#include <glm/gtc/quaternion.hpp>
#include <glm/mat3x3.hpp>

namespace sculpt::hal {
namespace {

constexpr std::string_view kSculptureAxes = "xyz";

Error problem(std::string_view spec, const std::string& what) {
  return Error("tracker axes \"" + std::string(spec) + "\": " + what +
               " (want three of x, y, z, each once, e.g. x,z,-y)");
}

}  // namespace

Result<glm::dquat> parse_tracker_axes(std::string_view spec) {
  // m[i][j]: how much of the tracker's axis j goes into the sculpture's i.
  std::array<std::array<double, 3>, 3> m{};
  std::array<bool, 3> used{};
  std::string_view rest = spec;
  for (int i = 0; i < 3; ++i) {
    const size_t comma = rest.find(',');
    std::string_view item = rest.substr(0, comma);
    if (i < 2 && comma == std::string_view::npos) return problem(spec, "fewer than three axes");
    if (i == 2 && comma != std::string_view::npos) return problem(spec, "more than three axes");
    rest = comma == std::string_view::npos ? std::string_view{} : rest.substr(comma + 1);
    double sign = 1.0;
    if (!item.empty() && (item.front() == '-' || item.front() == '+')) {
      sign = item.front() == '-' ? -1.0 : 1.0;
      item.remove_prefix(1);
    }
    const size_t axis = item.size() == 1 ? kSculptureAxes.find(item[0]) : std::string_view::npos;
    if (axis == std::string_view::npos) {
      std::string what = "\"";
      what.append(item).append("\" is not an axis");
      return problem(spec, what);
    }
    if (used[axis]) return problem(spec, std::string(item) + " is named twice");
    used[axis] = true;
    m[static_cast<size_t>(i)][axis] = sign;
  }
  // A signed permutation is a rotation when its determinant is +1.
  const double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                     m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                     m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  if (det < 0.0) return problem(spec, "a mirror image, not a rotation: flip the sign of one axis");
  glm::dmat3 r(1.0);
  for (int row = 0; row < 3; ++row)
    for (int col = 0; col < 3; ++col)
      r[col][row] = m[static_cast<size_t>(row)][static_cast<size_t>(col)];  // glm: [column][row]
  return glm::normalize(glm::quat_cast(r));
}

}  // namespace sculpt::hal
