#include "sculpt/core/tool/tool.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vector_relational.hpp>

#include "sculpt/base/atomic_file.h"
#include "sculpt/core/distance/signed_distance.h"
#include "sculpt/core/shapes/analytic_shapes.h"
#include "sculpt/core/util/parallel_for.h"

namespace sculpt::core {
namespace {

// A grid holding a shape of half-extents `half` (voxel units) centred on the
// grid centre, with one voxel of margin for the density ramp (d in [-1, 1]).
glm::ivec3 dims_for(glm::vec3 half) {
  return glm::ivec3(glm::ceil(2.0f * half + 2.0f)) + 1;
}

template <class SignedDistance>
Tool shape_tool(glm::vec3 half, float hardness, SignedDistance sd) {
  assert(hardness >= 0.0f && hardness <= 1.0f);
  const glm::ivec3 dims = dims_for(half);
  Tool tool{DenseGrid<uint8_t>(dims), grid_centre(dims), hardness};
  // Slices in parallel once the tool is big (a sculptor's 100-voxel ball
  // has eight million voxels, made while the next dab waits).
  constexpr int kSerialSlices = 64;
  const int threads = dims.z > kSerialSlices ? 0 : 1;
  // A softened tool tapers over its depth: the deepest voxel's distance
  // (within a voxel of the shape's, which the taper's width does not need
  // more precisely). A hard one needs no first pass.
  float depth = 0.0f;
  if (hardness < 1.0f) {
    std::vector<float> deepest(static_cast<size_t>(dims.z), 0.0f);
    parallel_for(
        dims.z,
        [&](int64_t slice) {
          const int z = static_cast<int>(slice);
          float m = 0.0f;
          for (int y = 0; y < dims.y; ++y)
            for (int x = 0; x < dims.x; ++x)
              m = std::min(m, sd(glm::vec3(x, y, z) - tool.pivot));
          deepest[static_cast<size_t>(slice)] = -m;
        },
        threads);
    depth = *std::max_element(deepest.begin(), deepest.end());
  }
  parallel_for(
      dims.z,
      [&](int64_t slice) {
        const int z = static_cast<int>(slice);
        for (int y = 0; y < dims.y; ++y)
          for (int x = 0; x < dims.x; ++x)
            tool.density.at(x, y, z) =
                tool_density(sd(glm::vec3(x, y, z) - tool.pivot), depth, hardness);
      },
      threads);
  return tool;
}

// make_sphere_tool() at hardness 1. A hard ball's density is 255 more than a
// voxel inside its surface and 0 more than a voxel outside
// (density_from_distance()'s ramp), so per row only the rim's few voxels at
// each end need their distance: the rest are filled. The same bytes as
// evaluating every voxel (tested); the bust's 110-voxel ball (11 million
// voxels, made while the next dab waits) 33 -> 3 ms.
Tool hard_ball_tool(float radius_vox) {
  const glm::ivec3 dims = dims_for(glm::vec3(radius_vox));
  Tool tool{DenseGrid<uint8_t>(dims, 0), grid_centre(dims), 1.0f};
  const double r = radius_vox;
  // Spans from the squared distances, with a voxel of distance to spare on
  // each side of the ramp, so float rounding in the exact part never meets
  // a filled voxel.
  const double inside2 = r > 2.0 ? (r - 2.0) * (r - 2.0) : -1.0;
  const double outside2 = (r + 2.0) * (r + 2.0);
  const auto ceil_in = [&](double x) {
    return std::clamp(static_cast<int>(std::ceil(x)), 0, dims.x);
  };
  parallel_for(
      dims.z,
      [&](int64_t slice) {
        const int z = static_cast<int>(slice);
        for (int y = 0; y < dims.y; ++y) {
          const double dy = y - static_cast<double>(tool.pivot.y);
          const double dz = z - static_cast<double>(tool.pivot.z);
          const double ryz2 = dy * dy + dz * dz;
          if (ryz2 >= outside2) continue;  // the whole row outside
          const double cx = tool.pivot.x;
          const double outer = std::sqrt(outside2 - ryz2) + 1.0;
          const int x0 = ceil_in(cx - outer), x3 = ceil_in(cx + outer);
          int x1 = x3, x2 = x3;  // [x1, x2): filled, deep inside
          if (ryz2 < inside2) {
            const double inner = std::sqrt(inside2 - ryz2) - 1.0;
            if (inner > 0.0) {
              x1 = std::max(ceil_in(cx - inner), x0);
              x2 = std::max(ceil_in(cx + inner), x1);
            }
          }
          uint8_t* row = &tool.density.at(0, y, z);
          const auto exact = [&](int x) {
            row[x] =
                density_from_distance(glm::length(glm::vec3(x, y, z) - tool.pivot) - radius_vox);
          };
          for (int x = x0; x < x1; ++x)
            exact(x);
          std::fill(row + x1, row + x2, uint8_t{255});
          for (int x = x2; x < x3; ++x)
            exact(x);
        }
      },
      dims.z > 64 ? 0 : 1);
  tool.sphere_radius_vox = radius_vox;
  return tool;
}

float segment_distance(glm::vec2 p, glm::vec2 a, glm::vec2 b) {
  const glm::vec2 ab = b - a;
  const float t = std::clamp(glm::dot(p - a, ab) / glm::dot(ab, ab), 0.0f, 1.0f);
  return glm::length(p - (a + t * ab));
}

}  // namespace

Status check_hardness(double hardness) {
  if (!(hardness >= 0.0 && hardness <= 1.0)) {
    std::ostringstream v;
    v << hardness;
    return Error("hardness must be a number in [0, 1], got " + v.str());
  }
  return {};
}

uint8_t tool_density(float d, float depth_vox, float hardness) {
  if (hardness >= 1.0f) return density_from_distance(d);
  // smoothstep: zero slope at both ends of the taper, so a partial-strength
  // stroke's swelling meets the untouched surface and its own crest without
  // a crease; the hard rim's linear ramp would leave a terrace there.
  const float width = 2.0f + (1.0f - hardness) * std::max(0.0f, depth_vox - 1.0f);
  const float t = std::clamp((1.0f - d) / width, 0.0f, 1.0f);
  return static_cast<uint8_t>(255.0f * t * t * (3.0f - 2.0f * t) + 0.5f);
}

glm::vec3 grid_centre(glm::ivec3 dims) {
  return (glm::vec3(dims) - 1.0f) * 0.5f;
}

Tool make_sphere_tool(float radius_vox, float hardness) {
  assert(radius_vox > 0.0f);
  if (hardness >= 1.0f) return hard_ball_tool(radius_vox);
  Tool tool = shape_tool(glm::vec3(radius_vox), hardness,
                         [&](glm::vec3 p) { return glm::length(p) - radius_vox; });
  tool.sphere_radius_vox = radius_vox;
  return tool;
}

Tool make_cube_tool(float edge_vox, float hardness) {
  assert(edge_vox > 0.0f);
  const glm::vec3 half(edge_vox * 0.5f);
  return shape_tool(half, hardness, [&](glm::vec3 p) {
    const glm::vec3 q = glm::abs(p) - half;
    return glm::length(glm::max(q, 0.0f)) + std::min(std::max(q.x, std::max(q.y, q.z)), 0.0f);
  });
}

Tool make_cylinder_tool(float radius_vox, float height_vox, float hardness) {
  assert(radius_vox > 0.0f && height_vox > 0.0f);
  return shape_tool(
      glm::vec3(radius_vox, radius_vox, height_vox * 0.5f), hardness, [&](glm::vec3 p) {
        const glm::vec2 q(std::hypot(p.x, p.y) - radius_vox, std::abs(p.z) - height_vox * 0.5f);
        return glm::length(glm::max(q, 0.0f)) + std::min(std::max(q.x, q.y), 0.0f);
      });
}

Tool make_ring_tool(float major_radius_vox, float minor_radius_vox, float hardness) {
  assert(major_radius_vox > 0.0f && minor_radius_vox > 0.0f);
  const float r = major_radius_vox + minor_radius_vox;
  return shape_tool(glm::vec3(r, r, minor_radius_vox), hardness, [&](glm::vec3 p) {
    return std::hypot(std::hypot(p.x, p.y) - major_radius_vox, p.z) - minor_radius_vox;
  });
}

Tool make_cone_tool(float radius_vox, float height_vox, float hardness) {
  assert(radius_vox > 0.0f && height_vox > 0.0f);
  const float h = height_vox * 0.5f;
  // The solid of revolution of the triangle (rho, z): base (0,-h)-(R,-h),
  // slant (R,-h)-(0,h); the axis is no boundary in 3D.
  return shape_tool(glm::vec3(radius_vox, radius_vox, h), hardness, [&](glm::vec3 p) {
    const glm::vec2 q(std::hypot(p.x, p.y), p.z);
    const float d = std::min(segment_distance(q, {0.0f, -h}, {radius_vox, -h}),
                             segment_distance(q, {radius_vox, -h}, {0.0f, h}));
    const bool inside = q.y >= -h && q.y <= h && q.x <= radius_vox * (h - q.y) / (2.0f * h);
    return inside ? -d : d;
  });
}

Tool with_hardness(Tool tool, float hardness) {
  assert(hardness >= 0.0f && hardness <= 1.0f);
  if (hardness >= 1.0f) return tool;
  if (tool.sphere_radius_vox > 0.0f) {
    return make_sphere_tool(tool.sphere_radius_vox, hardness);
  }
  // The exact sub-voxel distance of the 127.5 surface (Jones & Satherley's
  // shell initialisation), so a tool file softens like the analytic shapes.
  const DenseGrid<float> sd =
      signed_distance(tool.density, DistanceMethod::kExact, DistanceInit::kShell, 1);
  float depth = 0.0f;
  for (float v : sd.values())
    depth = std::max(depth, -v);
  for (size_t i = 0; i < sd.size(); ++i)
    tool.density[i] = tool_density(sd[i], depth, hardness);
  tool.hardness = hardness;
  return tool;
}

Tool tool_from_grid(DenseGrid<uint8_t> grid) {
  const glm::vec3 pivot = grid_centre(grid.dims());
  return Tool{std::move(grid), pivot};
}

Tool tool_from_volume(const Volume& volume, const Box& region) {
  return tool_from_grid(volume.read(region, 0));
}

Tool mirror_tool(const Tool& tool, int axis) {
  assert(axis >= 0 && axis < 3);
  const glm::ivec3 d = tool.density.dims();
  Tool out{DenseGrid<uint8_t>(d), tool.pivot, tool.hardness, tool.sphere_radius_vox};
  out.pivot[axis] = static_cast<float>(d[axis] - 1) - tool.pivot[axis];
  for (int z = 0; z < d.z; ++z)
    for (int y = 0; y < d.y; ++y)
      for (int x = 0; x < d.x; ++x) {
        glm::ivec3 s(x, y, z);
        s[axis] = d[axis] - 1 - s[axis];
        out.density.at(x, y, z) = tool.density.at(s.x, s.y, s.z);
      }
  return out;
}

Result<Tool> read_tool_nrrd(const std::filesystem::path& path, const NrrdLimits& limits) {
  auto grid = read_nrrd_u8(path, limits);
  if (!grid) return grid.error();
  Tool tool = tool_from_grid(std::move(grid.value()));
  // The header was valid for read_nrrd_u8, so it ends at the first empty line.
  std::ifstream in(path, std::ios::binary);
  const std::string key = "sculpt_pivot:=";
  for (std::string line; std::getline(in, line);) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) break;
    if (line.rfind(key, 0) != 0) continue;
    std::istringstream values(line.substr(key.size()));
    std::vector<float> v;
    for (float f; values >> f;)
      v.push_back(f);
    if (v.size() != 3 || !values.eof() || !std::isfinite(v[0]) || !std::isfinite(v[1]) ||
        !std::isfinite(v[2])) {
      return Error("sculpt_pivot: expected 3 finite numbers, got '" + line.substr(key.size()) + "'")
          .in(path.string());
    }
    // A pivot far outside the grid rotates the tool out of float precision
    // (`sculpt rotate` wrote "sizes: 0 0 0"): at most the grid's own size
    // beyond each face.
    const glm::vec3 dims(tool.density.dims());
    const glm::vec3 pivot(v[0], v[1], v[2]);
    if (glm::any(glm::lessThan(pivot, -dims)) || glm::any(glm::greaterThan(pivot, 2.0f * dims))) {
      return Error("sculpt_pivot: " + line.substr(key.size()) +
                   " is farther than the grid's size outside the grid")
          .in(path.string());
    }
    tool.pivot = pivot;
  }
  return tool;
}

Status write_tool_nrrd(const std::filesystem::path& path, const Tool& tool) {
  std::string header = nrrd_header_text(tool.density.dims(), NrrdType::kUInt8);
  // The header ends with its blank line; the key/value line goes before it.
  std::ostringstream pivot;
  pivot.precision(9);
  pivot << "sculpt_pivot:=" << tool.pivot.x << " " << tool.pivot.y << " " << tool.pivot.z << "\n";
  header.insert(header.size() - 1, pivot.str());
  AtomicFileWriter out(path);
  if (!out.ok()) return out.error();
  out.write(header);
  out.write(tool.density.data(), tool.density.size());
  return out.commit();
}

}  // namespace sculpt::core
