#include "sculpt/core/distance/signed_distance.h"
#include "sculpt/core/grid/grid_index.h"

#include <cmath>
#include <limits>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "sculpt/core/distance/brute_distance.h"
#include "sculpt/core/distance/chamfer_distance.h"
#include "sculpt/core/distance/exact_edt.h"
#include "sculpt/core/distance/octree_distance.h"
#include "sculpt/core/distance/vector_distance.h"
#include "sculpt/core/mesh/point_triangle.h"
#include "sculpt/core/util/parallel_for.h"
#include "sculpt/core/util/progress.h"

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
  return glm::vec3(grid_position(i, d));
}

void apply_sign(DenseGrid<float>& dist, const DenseGrid<uint8_t>& inside) {
  for (size_t i = 0; i < dist.size(); ++i)
    if (inside[i]) dist[i] = -dist[i];
}

// exact --init shell, the hybrid the paper names as future work. Each voxel
// must end with the distance to the nearest point of the triangulated
// surface, not to the nearest shell voxel: for a voxel D voxels away, the
// shell voxel centres lie in a jagged band about a voxel thick, so the
// nearest centre can sit several voxels along the surface from the true foot
// point (about sqrt(D) voxels), which on a curved surface costs up to a voxel
// (0.85 on the torus at 256^3 when each voxel measured to the points of its
// nearest shell voxel). So the hybrid propagates nearest *triangles*, a
// feature transform on the real surface rather than on voxel centres:
//  1. an exact feature transform to the shell voxels gives every voxel a
//     first triangle (the one holding its nearest shell voxel's closest
//     point);
//  2. triangles propagate along x, y and z lines, forward and back, twice:
//     a voxel takes its neighbour's triangle when that triangle is nearer to
//     it, measured exactly (Danielsson's vector propagation, with triangles
//     for vectors). Neighbouring voxels' feet lie on the same or adjacent
//     triangles, so the foot triangle usually arrives, or one next to it;
//  3. the triangles of the 2 x 2 x 2 cells within half a voxel of the foot
//     point of the triangle that arrived are measured, which finds the true
//     foot in most of the remaining cases.
// What is left: voxels near the medial axis, where feet far apart along the
// surface are almost equally near and the propagation can settle on the
// wrong one. Against the exact distance to the triangulation (octree, shell)
// at 64^3: worst 0.13 voxel, mean 0.0016 (sphere), worst 0.10, mean 0.0004
// (torus); without step 3, mean 0.005 / 0.002. Wider searches cut the mean
// further but cost several times as much (the search is most of the time).
// Shell voxels keep their own distances (exact, distance_shell.h).
DenseGrid<float> hybrid_exact(const DistanceInput& in, int threads, Progress* progress) {
  const DistanceShell& shell = *in.shell;
  const std::vector<Triangle3>& tris = in.surface->triangles();
  const glm::ivec3 d = in.phi.dims();
  const size_t slice = size_t(d.x) * d.y;
  DenseGrid<uint8_t> seeds(d, 0);
  for (int32_t v : shell.voxels)
    seeds[size_t(v)] = 1;
  DenseGrid<float> best2(d, kInf);
  DenseGrid<int32_t> cand(d, -1);
  // Units: the feature transform counts as one pass over the slices, then
  // each loop below steps once per slice (z) or row (y).
  ProgressStage stage(progress, 0.0, 1.0, int64_t(d.z) * 7 + int64_t(d.y) * 2);
  stage.step(0);
  if (stage.cancelled()) return DenseGrid<float>(d, kInf);
  {
    const FeatureTransform ft = feature_transform(seeds, 1, threads);
    stage.step(d.z);
    parallel_for(
        d.z,
        [&](int64_t z) {
          for (size_t i = size_t(z) * slice; i < size_t(z + 1) * slice; ++i) {
            const int32_t s = ft.nearest[i];
            if (s < 0) continue;
            const size_t k = size_t(shell.slot[size_t(s)]);
            const int32_t t = shell.triangle[k];
            cand[i] = t;
            if (shell.slot[i] >= 0) {
              best2[i] = shell.distance[k] * shell.distance[k];
            } else if (t >= 0) {
              const Triangle3& tri = tris[size_t(t)];
              best2[i] = triangle_distance2(voxel_position(d, int64_t(i)), tri.a, tri.b - tri.a,
                                            tri.c - tri.a);
            }
          }
        },
        threads, stage);
  }
  // Offers the triangle of voxel q to voxel p (not a shell voxel). Along a
  // line most neighbours hold the same triangle, which costs one compare.
  auto offer = [&](size_t p, size_t q, glm::vec3 pos) {
    const int32_t t = cand[q];
    if (t < 0 || t == cand[p] || shell.slot[p] >= 0) return;
    const Triangle3& tri = tris[size_t(t)];
    const float l = triangle_distance2(pos, tri.a, tri.b - tri.a, tri.c - tri.a);
    if (l < best2[p]) {
      best2[p] = l;
      cand[p] = t;
    }
  };
  for (int round = 0; round < 2; ++round) {
    // x lines, per z-slice.
    parallel_for(
        d.z,
        [&](int64_t z) {
          for (int y = 0; y < d.y; ++y) {
            const size_t r = size_t(z) * slice + size_t(y) * d.x;
            for (int x = 1; x < d.x; ++x)
              offer(r + x, r + x - 1, glm::vec3(float(x), float(y), float(z)));
            for (int x = d.x - 2; x >= 0; --x)
              offer(r + x, r + x + 1, glm::vec3(float(x), float(y), float(z)));
          }
        },
        threads, stage);
    // y lines, per z-slice, a row at a time.
    parallel_for(
        d.z,
        [&](int64_t z) {
          for (int y = 1; y < d.y; ++y) {
            const size_t r = size_t(z) * slice + size_t(y) * d.x;
            for (int x = 0; x < d.x; ++x)
              offer(r + x, r + x - d.x, glm::vec3(float(x), float(y), float(z)));
          }
          for (int y = d.y - 2; y >= 0; --y) {
            const size_t r = size_t(z) * slice + size_t(y) * d.x;
            for (int x = 0; x < d.x; ++x)
              offer(r + x, r + x + d.x, glm::vec3(float(x), float(y), float(z)));
          }
        },
        threads, stage);
    // z lines, per y, a row at a time.
    parallel_for(
        d.y,
        [&](int64_t y) {
          for (int z = 1; z < d.z; ++z) {
            const size_t r = size_t(z) * slice + size_t(y) * d.x;
            for (int x = 0; x < d.x; ++x)
              offer(r + x, r + x - slice, glm::vec3(float(x), float(y), float(z)));
          }
          for (int z = d.z - 2; z >= 0; --z) {
            const size_t r = size_t(z) * slice + size_t(y) * d.x;
            for (int x = 0; x < d.x; ++x)
              offer(r + x, r + x + slice, glm::vec3(float(x), float(y), float(z)));
          }
        },
        threads, stage);
  }
  DenseGrid<float> out(d, kInf);
  parallel_for(
      d.z,
      [&](int64_t z) {
        for (size_t i = size_t(z) * slice; i < size_t(z + 1) * slice; ++i) {
          const int32_t own = shell.slot[i];
          if (own >= 0) {
            out[i] = std::abs(shell.distance[size_t(own)]);
            continue;
          }
          const int32_t t = cand[i];
          if (t < 0) continue;
          const glm::vec3 pos = voxel_position(d, int64_t(i));
          const Triangle3& tri = tris[size_t(t)];
          const glm::vec3 c = closest_point_on_triangle(pos, tri.a, tri.b, tri.c).point;
          // The cells within half a voxel of the foot point (2 x 2 x 2).
          const glm::ivec3 lo(glm::floor(c - 0.5f)), hi(glm::floor(c + 0.5f));
          out[i] = std::sqrt(
              in.surface->nearest_in_cells(pos, lo, hi, {c, best2[i], t}).distance_squared);
        }
      },
      threads, stage);
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

DistanceInput prepare_distance_input(DenseGrid<float> phi, DistanceInit init, int threads,
                                     Progress* progress) {
  DistanceInput in;
  // The two shell steps take about the same time; the mask is quick.
  if (progress != nullptr && !progress->report(0.0)) return in;
  in.inside = inside_mask(phi);
  if (init == DistanceInit::kBinary) {
    in.boundary = boundary_voxels(in.inside, threads);
  } else {
    in.surface.emplace(phi, threads);
    if (progress != nullptr && !progress->report(0.5)) return in;
    in.shell = distance_shell(phi, *in.surface, threads);
  }
  if (progress != nullptr) progress->report(1.0);
  in.phi = std::move(phi);
  return in;
}

DenseGrid<float> compute_signed_distance(const DistanceInput& in, DistanceMethod method,
                                         DistanceInit init, int threads, Progress* progress) {
  const glm::ivec3 d = in.phi.dims();
  if (progress != nullptr && !progress->report(0.0)) return DenseGrid<float>(d, kInf);
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
      out = binary ? exact_edt(in.boundary, 1, threads) : hybrid_exact(in, threads, progress);
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
  if (cancelled(progress)) return out;
  apply_sign(out, in.inside);
  if (progress != nullptr) progress->report(1.0);
  return out;
}

DenseGrid<float> signed_distance(const DenseGrid<float>& phi, DistanceMethod method,
                                 DistanceInit init, int threads, Progress* progress) {
  SubProgress prepare(progress, 0.0, 0.3), compute(progress, 0.3, 1.0);
  const DistanceInput in = prepare_distance_input(phi, init, threads, prepare.get());
  if (cancelled(progress)) return DenseGrid<float>(phi.dims(), kInf);
  return compute_signed_distance(in, method, init, threads, compute.get());
}

DenseGrid<float> signed_distance(const DenseGrid<uint8_t>& density, DistanceMethod method,
                                 DistanceInit init, int threads) {
  return signed_distance(level_function(density), method, init, threads);
}

}  // namespace sculpt::core
