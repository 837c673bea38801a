#include "sculpt/core/distance/signed_distance.h"

#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

#include "sculpt/core/distance/brute_distance.h"
#include "sculpt/core/distance/chamfer_distance.h"
#include "sculpt/core/distance/exact_edt.h"
#include "sculpt/core/distance/octree_distance.h"
#include "sculpt/core/distance/vector_distance.h"
#include "sculpt/core/util/parallel_for.h"

namespace sculpt::core {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

struct MethodName {
  DistanceMethod method;
  const char* name;
};
constexpr MethodName kMethods[] = {
    {DistanceMethod::kBrute, "brute"},
    {DistanceMethod::kExact, "exact"},
    {DistanceMethod::kOctree, "octree"},
    {DistanceMethod::kChamferCity, "chamfer-city"},
    {DistanceMethod::kChamfer345, "chamfer-345"},
    {DistanceMethod::kChamfer5x5x5, "chamfer-5x5x5"},
    {DistanceMethod::kEvdt, "evdt"},
    {DistanceMethod::kVcvdt, "vcvdt"},
};

glm::vec3 voxel_position(glm::ivec3 d, int64_t i) {
  return glm::vec3(float(i % d.x), float((i / d.x) % d.y), float(i / (int64_t(d.x) * d.y)));
}

void apply_sign(DenseGrid<float>& dist, const DenseGrid<uint8_t>& inside) {
  for (size_t i = 0; i < dist.size(); ++i)
    if (inside[i]) dist[i] = -dist[i];
}

// exact --init shell: the nearest shell voxel by an exact feature transform,
// then the true distance to the surface points known around it.
DenseGrid<float> hybrid_exact(const DistanceInput& in, int threads) {
  const DistanceShell& shell = *in.shell;
  const glm::ivec3 d = in.phi.dims();
  DenseGrid<uint8_t> seeds(d, 0);
  for (int32_t v : shell.voxels)
    seeds[size_t(v)] = 1;
  const FeatureTransform ft = feature_transform(seeds, 1, threads);
  DenseGrid<float> out(d);
  parallel_for(
      d.z,
      [&](int64_t z) {
        const size_t slice = size_t(d.x) * d.y;
        for (size_t i = size_t(z) * slice; i < size_t(z + 1) * slice; ++i) {
          const int32_t own = shell.slot[i];
          if (own >= 0) {
            out[i] = std::abs(shell.distance[own]);
            continue;
          }
          const int32_t s = ft.nearest[i];
          if (s < 0) {
            out[i] = kInf;
            continue;
          }
          const glm::vec3 p = voxel_position(d, int64_t(i));
          float best = kInf;
          // The closest surface points of the nearest shell voxel and its
          // neighbours: points sampled about a voxel apart on the surface,
          // so on a curved surface the result can exceed the true distance
          // by a few hundredths of a voxel (measured in the README table).
          const glm::ivec3 sc(voxel_position(d, s));
          for (int dz = -1; dz <= 1; ++dz)
            for (int dy = -1; dy <= 1; ++dy)
              for (int dx = -1; dx <= 1; ++dx) {
                const glm::ivec3 q = sc + glm::ivec3(dx, dy, dz);
                if (!shell.slot.in_bounds(q.x, q.y, q.z)) continue;
                const int32_t k = shell.slot.at(q.x, q.y, q.z);
                if (k < 0) continue;
                const glm::vec3 v = p - shell.closest[k];
                best = std::min(best, glm::dot(v, v));
              }
          out[i] = std::sqrt(best);
        }
      },
      threads);
  return out;
}

}  // namespace

const char* distance_method_name(DistanceMethod method) {
  for (const auto& m : kMethods)
    if (m.method == method) return m.name;
  return "?";
}

const char* distance_init_name(DistanceInit init) {
  return init == DistanceInit::kBinary ? "binary" : "shell";
}

Result<DistanceMethod> parse_distance_method(const std::string& name) {
  for (const auto& m : kMethods)
    if (name == m.name) return m.method;
  return Error("--method: unknown method '" + name +
               "' (brute, exact, octree, chamfer-city, chamfer-345, chamfer-5x5x5, evdt, vcvdt)");
}

Result<DistanceInit> parse_distance_init(const std::string& name) {
  if (name == "binary") return DistanceInit::kBinary;
  if (name == "shell") return DistanceInit::kShell;
  return Error("--init: unknown initialisation '" + name + "' (binary, shell)");
}

DistanceInput prepare_distance_input(DenseGrid<float> phi, DistanceInit init, int threads) {
  DistanceInput in;
  in.inside = inside_mask(phi);
  if (init == DistanceInit::kBinary) {
    in.boundary = boundary_voxels(in.inside, threads);
  } else {
    in.surface.emplace(phi, threads);
    in.shell = distance_shell(phi, *in.surface, threads);
  }
  in.phi = std::move(phi);
  return in;
}

DenseGrid<float> compute_signed_distance(const DistanceInput& in, DistanceMethod method,
                                         DistanceInit init, int threads) {
  const glm::ivec3 d = in.phi.dims();
  const bool binary = init == DistanceInit::kBinary;
  assert(binary || in.shell.has_value());
  DenseGrid<float> out;
  switch (method) {
    case DistanceMethod::kBrute:
      out = binary ? brute_distance_to_points(d, voxel_positions(in.boundary, 1), threads)
                   : brute_distance_to_triangles(d, in.surface->triangles(), threads);
      break;
    case DistanceMethod::kOctree:
      out = binary ? octree_distance_to_points(d, voxel_positions(in.boundary, 1), threads)
                   : octree_distance_to_triangles(d, in.surface->triangles(), threads);
      break;
    case DistanceMethod::kExact:
      out = binary ? exact_edt(in.boundary, 1, threads) : hybrid_exact(in, threads);
      break;
    case DistanceMethod::kChamferCity:
    case DistanceMethod::kChamfer345:
    case DistanceMethod::kChamfer5x5x5: {
      DenseGrid<float> init_field(d, kInf);
      if (binary) {
        for (size_t i = 0; i < init_field.size(); ++i)
          if (in.boundary[i]) init_field[i] = 0.0f;
      } else {
        for (size_t k = 0; k < in.shell->voxels.size(); ++k)
          init_field[size_t(in.shell->voxels[k])] = std::abs(in.shell->distance[k]);
      }
      const ChamferMask mask = method == DistanceMethod::kChamferCity  ? ChamferMask::kCity
                               : method == DistanceMethod::kChamfer345 ? ChamferMask::k345
                                                                       : ChamferMask::k5x5x5;
      out = chamfer_distance(init_field, mask);
      break;
    }
    case DistanceMethod::kEvdt:
    case DistanceMethod::kVcvdt: {
      std::vector<VectorSeed> seeds;
      if (binary) {
        for (size_t i = 0; i < in.boundary.size(); ++i)
          if (in.boundary[i]) seeds.push_back({int32_t(i), glm::vec3(0.0f)});
      } else {
        for (size_t k = 0; k < in.shell->voxels.size(); ++k) {
          const int32_t v = in.shell->voxels[k];
          seeds.push_back({v, in.shell->closest[k] - voxel_position(d, v)});
        }
      }
      out = vector_distance(
          d, seeds, method == DistanceMethod::kEvdt ? VectorScheme::kEvdt : VectorScheme::kVcvdt);
      break;
    }
  }
  apply_sign(out, in.inside);
  return out;
}

DenseGrid<float> signed_distance(const DenseGrid<float>& phi, DistanceMethod method,
                                 DistanceInit init, int threads) {
  const DistanceInput in = prepare_distance_input(phi, init, threads);
  return compute_signed_distance(in, method, init, threads);
}

DenseGrid<float> signed_distance(const DenseGrid<uint8_t>& density, DistanceMethod method,
                                 DistanceInit init, int threads) {
  return signed_distance(level_function(density), method, init, threads);
}

}  // namespace sculpt::core
