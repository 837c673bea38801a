// Surface benchmarks (issue 4). Workload: the peers.py sphere
// (core::sphere_volume, radius 0.35 n). Compare full extraction with
//   /usr/bin/python3 ../shared/bench/peers.py mc --sizes 128,256
// run in the same session (vtkFlyingEdges3D prints its thread count; our
// "threads" counter is the thread count of the extraction).

#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <memory>
#include <vector>

#include <glm/geometric.hpp>

#include "sculpt/core/mesh/mesh_cache.h"
#include "sculpt/core/shapes/analytic_shapes.h"
#include "sculpt/core/util/parallel_for.h"
#include "sculpt/core/volume/volume.h"

namespace sculpt::core {
namespace {

// Volumes are built once per size: building a 512^3 sphere takes seconds.
Volume& sphere(int n) {
  static std::map<int, std::unique_ptr<Volume>> volumes;
  auto& v = volumes[n];
  if (!v) v = std::make_unique<Volume>(sphere_volume(n));
  return *v;
}

// Full extraction: every brick decoded once and marched, into the per-brick
// meshes the renderer draws (range(2) = 1: also welded into one indexed mesh,
// as for export).
void BM_MeshExtract(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const int threads = static_cast<int>(state.range(1));
  const bool weld = state.range(2) != 0;
  const Volume& volume = sphere(n);
  int64_t triangles = 0;
  for (auto _ : state) {
    MeshCache cache(0, MarchingCubesOptions{127.5f, threads});
    cache.update(volume);
    triangles = cache.triangle_count();
    if (weld) {
      Mesh mesh = cache.welded_mesh();
      benchmark::DoNotOptimize(mesh);
    }
  }
  state.counters["threads"] = threads == 0 ? hardware_threads() : threads;
  state.counters["triangles"] = static_cast<double>(triangles);
}
BENCHMARK(BM_MeshExtract)
    ->ArgsProduct({{128, 256}, {1, 0}, {0, 1}})
    ->ArgNames({"n", "threads", "weld"})
    ->Unit(benchmark::kMillisecond);

// Re-meshing after one dab: a ball of radius 14 (its density ramp fills a
// 32^3 box) added or carved at a point of the surface, not aligned with the
// bricks, so it touches up to 8 bricks. Only the update is timed; the edit
// (decode, apply, re-encode) is the sculpting side's cost.
void BM_MeshRemeshAfterDab(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  Volume volume = sphere_volume(n);
  MeshCache cache(0);
  cache.update(volume);
  const glm::vec3 centre(static_cast<float>(n - 1) / 2.0f);
  const float radius = 0.35f * static_cast<float>(n);
  const float dab_radius = 14.0f;
  std::vector<double> samples;
  int64_t meshed = 0;
  uint32_t seed = 12345;
  auto next = [&] {
    seed = seed * 1664525u + 1013904223u;
    return static_cast<float>(seed >> 8) / static_cast<float>(1u << 24) * 2.0f - 1.0f;
  };
  bool carve = false;
  for (auto _ : state) {
    glm::vec3 dir;
    do
      dir = glm::vec3(next(), next(), next());
    while (glm::dot(dir, dir) < 0.01f || glm::dot(dir, dir) > 1.0f);
    const glm::vec3 at = centre + radius * glm::normalize(dir);
    const Box box{glm::ivec3(glm::floor(at)) - 16, glm::ivec3(glm::floor(at)) + 16};
    const int e = volume.brick_edge();
    volume.edit(box, [&](glm::ivec3 origin, std::span<uint8_t> voxels) {
      const Box local = intersect(box, Box{origin, origin + e});
      for (int z = local.lo.z; z < local.hi.z; ++z)
        for (int y = local.lo.y; y < local.hi.y; ++y)
          for (int x = local.lo.x; x < local.hi.x; ++x) {
            const glm::vec3 p = glm::vec3(x, y, z) - at;
            const uint8_t ball = density_from_distance(std::sqrt(glm::dot(p, p)) - dab_radius);
            uint8_t& v = voxels[(static_cast<size_t>(z - origin.z) * e + (y - origin.y)) * e +
                                (x - origin.x)];
            v = carve ? std::min<uint8_t>(v, static_cast<uint8_t>(255 - ball)) : std::max(v, ball);
          }
    });
    carve = !carve;
    const auto t0 = std::chrono::steady_clock::now();
    const MeshUpdate u = cache.update(volume);
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    state.SetIterationTime(s);
    samples.push_back(s);
    meshed += u.bricks_meshed;
  }
  std::sort(samples.begin(), samples.end());
  auto pct = [&](double p) {
    return samples[std::min(samples.size() - 1,
                            static_cast<size_t>(p * static_cast<double>(samples.size())))];
  };
  state.counters["median_us"] = pct(0.5) * 1e6;
  state.counters["p99_us"] = pct(0.99) * 1e6;
  state.counters["bricks_meshed"] =
      static_cast<double>(meshed) / static_cast<double>(samples.size());
  state.counters["threads"] = hardware_threads();
}
BENCHMARK(BM_MeshRemeshAfterDab)
    ->Arg(256)
    ->Arg(512)
    ->ArgName("n")
    ->UseManualTime()
    ->Iterations(500)
    ->Unit(benchmark::kMicrosecond);

// A coarse view: level 2 (4^3 voxels averaged) of a 512^3 volume.
void BM_MeshLevel(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const int level = static_cast<int>(state.range(1));
  const Volume& volume = sphere(n);
  int64_t triangles = 0;
  for (auto _ : state) {
    MeshCache cache(level);
    cache.update(volume);
    triangles = cache.triangle_count();
  }
  state.counters["triangles"] = static_cast<double>(triangles);
  state.counters["threads"] = hardware_threads();
}
BENCHMARK(BM_MeshLevel)->Args({512, 2})->ArgNames({"n", "level"})->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace sculpt::core
