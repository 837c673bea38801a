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

#include <sys/resource.h>

#include <glm/geometric.hpp>

#include "sculpt/core/mesh/brick_simplify.h"
#include "sculpt/core/mesh/marching_cubes.h"
#include "sculpt/core/mesh/mesh_cache.h"
#include "sculpt/core/mesh/mixed_level_mesh.h"
#include "sculpt/core/shapes/analytic_shapes.h"
#include "sculpt/core/util/parallel_for.h"
#include "sculpt/core/volume/stored_voxels.h"
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

// Minor page faults of the process so far.
long minor_page_faults() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_minflt;
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
  MeshUpdate stats;
  const long faults_before = minor_page_faults();
  for (auto _ : state) {
    MeshCache cache(0, MarchingCubesOptions{127.5f, threads});
    stats = cache.update(volume);
    triangles = cache.triangle_count();
    if (weld) {
      Mesh mesh = cache.welded_mesh();
      benchmark::DoNotOptimize(mesh);
    }
  }
  state.counters["threads"] = threads == 0 ? hardware_threads() : threads;
  state.counters["triangles"] = static_cast<double>(triangles);
  // Fresh memory the extraction touches (its output, mostly): each page
  // costs a kernel fault, a large share of the time.
  state.counters["faults"] = benchmark::Counter(
      static_cast<double>(minor_page_faults() - faults_before), benchmark::Counter::kAvgIterations);
  state.counters["decoded"] = static_cast<double>(stats.bricks_decoded);
  state.counters["marched"] = static_cast<double>(stats.bricks_meshed);
}
BENCHMARK(BM_MeshExtract)
    ->ArgsProduct({{128, 256}, {1, 0}, {0, 1}})
    ->ArgNames({"n", "threads", "weld"})
    ->Unit(benchmark::kMillisecond);

// The march alone, as the mesher runs it on each stale brick: every 32^3
// brick of the 256^3 peers.py sphere that its surface crosses, its 35^3
// samples filled once, marched into meshes kept between iterations (so
// their memory is reused, as the mesher's is). Counters: triangles a pass,
// and ns per triangle.
void BM_MarchBricks(benchmark::State& state) {
  constexpr int kEdge = 32, kN = 256;
  const float radius = 0.35f * kN;
  const glm::vec3 centre(static_cast<float>(kN - 1) / 2.0f);
  std::vector<std::vector<uint8_t>> blocks;
  std::vector<glm::ivec3> origins;
  for (int bz = 0; bz < kN / kEdge; ++bz)
    for (int by = 0; by < kN / kEdge; ++by)
      for (int bx = 0; bx < kN / kEdge; ++bx) {
        const glm::ivec3 lo = glm::ivec3(bx, by, bz) * kEdge - 1;
        const Box box{lo, lo + kEdge + 3};
        std::vector<uint8_t> voxels(static_cast<size_t>(box.voxel_count()));
        fill_sphere(box, centre, radius, voxels);
        const auto [lo_v, hi_v] = std::minmax_element(voxels.begin(), voxels.end());
        if (*hi_v < 128 || *lo_v > 127) continue;
        blocks.push_back(std::move(voxels));
        origins.push_back(glm::ivec3(bx, by, bz) * kEdge);
      }
  std::vector<BrickMesh> meshes(blocks.size());
  int64_t triangles = 0;
  for (auto _ : state) {
    triangles = 0;
    for (size_t i = 0; i < blocks.size(); ++i) {
      MarchBlock block;
      block.voxels = blocks[i].data();
      block.cells = glm::ivec3(kEdge);
      block.origin = origins[i];
      block.level_dims = glm::ivec3(kN);
      march_block(block, meshes[i]);
      triangles += static_cast<int64_t>(meshes[i].mesh.triangles.size());
    }
  }
  state.counters["bricks"] = static_cast<double>(blocks.size());
  state.counters["triangles"] = static_cast<double>(triangles);
  state.counters["ns_per_triangle"] = benchmark::Counter(
      static_cast<double>(triangles) * 1e-9,
      benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_MarchBricks)->Unit(benchmark::kMillisecond);

// A ball of radius 14 (its density ramp fills a 32^3 box) added or carved
// at a random point of the surface of the peers.py sphere that fills
// `volume`, not aligned with the bricks, so it touches up to 8 bricks.
// Uniform numbers in [-1, 1) from a fixed seed, the same every run.
struct Uniform {
  uint32_t seed = 12345;
  float operator()() {
    seed = seed * 1664525u + 1013904223u;
    return static_cast<float>(seed >> 8) / static_cast<float>(1u << 24) * 2.0f - 1.0f;
  }
};

// Returns the box it edited.
template <class Random>
Box dab_on_surface(Volume& volume, Random& next, bool carve, float dab_radius = 14.0f) {
  const glm::vec3 centre(static_cast<float>(volume.dims().x - 1) / 2.0f);
  const float radius = 0.35f * static_cast<float>(volume.dims().x);
  glm::vec3 dir;
  do
    dir = glm::vec3(next(), next(), next());
  while (glm::dot(dir, dir) < 0.01f || glm::dot(dir, dir) > 1.0f);
  const glm::vec3 at = centre + radius * glm::normalize(dir);
  const int half = static_cast<int>(std::ceil(dab_radius)) + 2;  // the density ramp's reach
  const Box box{glm::ivec3(glm::floor(at)) - half, glm::ivec3(glm::floor(at)) + half};
  const int e = volume.brick_edge();
  volume.edit(box, [&](glm::ivec3 origin, std::span<uint8_t> voxels) {
    const Box local = intersect(box, Box{origin, origin + e});
    for (int z = local.lo.z; z < local.hi.z; ++z)
      for (int y = local.lo.y; y < local.hi.y; ++y)
        for (int x = local.lo.x; x < local.hi.x; ++x) {
          const glm::vec3 p = glm::vec3(x, y, z) - at;
          const uint8_t ball = density_from_distance(std::sqrt(glm::dot(p, p)) - dab_radius);
          uint8_t& v =
              voxels[(static_cast<size_t>(z - origin.z) * e + (y - origin.y)) * e + (x - origin.x)];
          v = carve ? std::min<uint8_t>(v, static_cast<uint8_t>(255 - ball)) : std::max(v, ball);
        }
  });
  return box;
}

// Re-meshing after one dab: a ball of radius 14 (its density ramp fills a
// 32^3 box) added or carved at a point of the surface, not aligned with the
// bricks, so it touches up to 8 bricks. Only the update is timed; the edit
// (decode, apply, re-encode) is the sculpting side's cost.
void BM_MeshRemeshAfterDab(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  Volume volume = sphere_volume(n);
  MeshCache cache(0);
  cache.update(volume);
  std::vector<double> samples;
  int64_t meshed = 0;
  Uniform next;
  bool carve = false;
  for (auto _ : state) {
    dab_on_surface(volume, next, carve);
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

// Per-brick levels as a view-distance LOD gives them: level 0 within 64
// voxels of a camera point on the +x side, one level coarser per 64 voxels
// beyond, at most 3.
std::vector<int> camera_levels(const Volume& volume) {
  const glm::ivec3 g = volume.brick_grid();
  const glm::vec3 eye(static_cast<float>(volume.dims().x),
                      static_cast<float>(volume.dims().y) / 2.0f,
                      static_cast<float>(volume.dims().z) / 2.0f);
  std::vector<int> levels;
  for (int z = 0; z < g.z; ++z)
    for (int y = 0; y < g.y; ++y)
      for (int x = 0; x < g.x; ++x) {
        const glm::vec3 c = (glm::vec3(x, y, z) + 0.5f) * static_cast<float>(volume.brick_edge());
        levels.push_back(std::min(3, static_cast<int>(glm::length(c - eye) / 64.0f)));
      }
  return levels;
}

// Mixed levels from scratch (every brick meshed at its level and stitched).
void BM_MeshMixedLevel(benchmark::State& state) {
  const Volume& volume = sphere(static_cast<int>(state.range(0)));
  const std::vector<int> levels = camera_levels(volume);
  int64_t triangles = 0;
  for (auto _ : state) {
    MixedLevelMeshCache cache;
    cache.update(volume, levels);
    triangles = cache.triangle_count();
  }
  state.counters["triangles"] = static_cast<double>(triangles);
}
BENCHMARK(BM_MeshMixedLevel)->Arg(256)->ArgName("n")->Unit(benchmark::kMillisecond);

// The mixed-level cache updated after each of the benchmark's dabs (balls
// of `dab_radius` added and carved in turn at random points of the
// sphere's surface); only the updates are timed.
struct UpdatesAfterDabs {
  std::vector<double> seconds;  // sorted
  double bricks_remeshed = 0;   // per update
};

UpdatesAfterDabs time_updates_after_dabs(benchmark::State& state, Volume& volume,
                                         MixedLevelMeshCache& cache, const std::vector<int>& levels,
                                         float dab_radius) {
  cache.update(volume, levels);
  Uniform next;
  UpdatesAfterDabs out;
  int64_t meshed = 0;
  bool carve = false;
  for (auto _ : state) {
    dab_on_surface(volume, next, carve, dab_radius);
    carve = !carve;
    const auto t0 = std::chrono::steady_clock::now();
    const MeshUpdate u = cache.update(volume, levels);
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    state.SetIterationTime(s);
    out.seconds.push_back(s);
    meshed += u.bricks_changed;
  }
  std::sort(out.seconds.begin(), out.seconds.end());
  out.bricks_remeshed = static_cast<double>(meshed) / static_cast<double>(out.seconds.size());
  return out;
}

// The mixed-level cache after one dab (same dabs as BM_MeshRemeshAfterDab).
void BM_MeshMixedLevelAfterDab(benchmark::State& state) {
  Volume volume = sphere_volume(static_cast<int>(state.range(0)));
  const std::vector<int> levels = camera_levels(volume);
  MixedLevelMeshCache cache;
  const UpdatesAfterDabs u = time_updates_after_dabs(state, volume, cache, levels, 14.0f);
  const std::vector<double>& t = u.seconds;
  state.counters["median_us"] = t[t.size() / 2] * 1e6;
  state.counters["p99_us"] = t[std::min(t.size() - 1, t.size() * 99 / 100)] * 1e6;
  state.counters["bricks_remeshed"] = u.bricks_remeshed;
}
BENCHMARK(BM_MeshMixedLevelAfterDab)
    ->Arg(256)
    ->Arg(512)
    ->ArgName("n")
    ->UseManualTime()
    ->Iterations(100)
    ->Unit(benchmark::kMicrosecond);

// The station's worst change: the demo's head ball (radius 66) added or
// carved on the 256^3 sphere, every brick at level 0 (the window's full
// detail), the mixed-level cache updated after it.
void BM_MeshMixedLevelAfterBigDab(benchmark::State& state) {
  Volume volume = sphere_volume(256);
  const std::vector<int> levels(static_cast<size_t>(volume.brick_count()), 0);
  MarchingCubesOptions options;
  options.threads = static_cast<int>(state.range(0));
  MixedLevelMeshCache cache(options);
  const UpdatesAfterDabs u = time_updates_after_dabs(state, volume, cache, levels, 66.0f);
  state.counters["median_ms"] = u.seconds[u.seconds.size() / 2] * 1e3;
  state.counters["bricks_remeshed"] = u.bricks_remeshed;
}
BENCHMARK(BM_MeshMixedLevelAfterBigDab)
    ->Arg(1)
    ->Arg(2)
    ->ArgName("threads")
    ->UseManualTime()
    ->Iterations(20)
    ->Unit(benchmark::kMillisecond);

// The update after the head ball as the window's mesher makes it: the
// bricks' voxels given by the sculptor (not decoded), with (`box` 1) or
// without (0) where they changed since the version the cache holds, so
// only there are they compared to find what moved.
void BM_MeshMixedLevelAfterBigDabGiven(benchmark::State& state) {
  Volume volume = sphere_volume(256);
  const bool with_box = state.range(0) != 0;
  const std::vector<int> levels(static_cast<size_t>(volume.brick_count()), 0);
  MarchingCubesOptions options;
  options.threads = 2;
  MixedLevelMeshCache cache(options);
  cache.update(volume, levels);
  Uniform next;
  bool carve = false;
  const int e = volume.brick_edge();
  int64_t compared_in_part = 0;
  for (auto _ : state) {
    std::vector<uint64_t> before(static_cast<size_t>(volume.brick_count()));
    for (size_t i = 0; i < before.size(); ++i)
      before[i] = volume.brick_version(grid_position(static_cast<int64_t>(i), volume.brick_grid()));
    const Box box = dab_on_surface(volume, next, carve, 66.0f);
    carve = !carve;
    StoredVoxelsByBrick stored;
    const Box bricks = volume.bricks_overlapping(box);
    for (int z = bricks.lo.z; z < bricks.hi.z; ++z)
      for (int y = bricks.lo.y; y < bricks.hi.y; ++y)
        for (int x = bricks.lo.x; x < bricks.hi.x; ++x) {
          const glm::ivec3 b(x, y, z);
          const auto i = static_cast<int64_t>(grid_index(b, volume.brick_grid()));
          StoredVoxels& s = stored[i];
          s.version = volume.brick_version(b);
          s.voxels.resize(static_cast<size_t>(e) * e * e);
          volume.decode_brick(b, s.voxels);
          if (with_box) {
            s.changed_from = before[static_cast<size_t>(i)];
            s.changed = box;
          }
        }
    const auto t0 = std::chrono::steady_clock::now();
    compared_in_part += cache.update(volume, levels, &stored).bricks_compared_where_changed;
    state.SetIterationTime(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  state.counters["bricks_compared_where_changed"] =
      static_cast<double>(compared_in_part) / static_cast<double>(state.iterations());
}
BENCHMARK(BM_MeshMixedLevelAfterBigDabGiven)
    ->Arg(0)
    ->Arg(1)
    ->ArgName("box")
    ->UseManualTime()
    ->Iterations(20)
    ->Unit(benchmark::kMillisecond);

// Coarse first for a sculpting change, measured: the head ball's changed
// bricks shown at `level` first (their unchanged neighbours re-stitch
// against them), then at full detail. Timed: the coarse pass. The window
// does not do this (surface_mesher.cpp): the neighbours' re-stitching makes
// the coarse pass slower than the full-detail update it would precede
// (compare BM_MeshMixedLevelAfterBigDab/threads:2).
void BM_MeshMixedLevelCoarseFirstAfterBigDab(benchmark::State& state) {
  Volume volume = sphere_volume(256);
  const int level = static_cast<int>(state.range(0));
  const std::vector<int> full(static_cast<size_t>(volume.brick_count()), 0);
  MarchingCubesOptions options;
  options.threads = 2;
  MixedLevelMeshCache cache(options);
  cache.update(volume, full);
  Uniform next;
  const glm::ivec3 grid = volume.brick_grid();
  std::vector<uint64_t> versions(full.size());
  double coarse_s = 0, full_s = 0, coarse_meshed = 0;
  bool carve = false;
  for (auto _ : state) {
    for (size_t i = 0; i < versions.size(); ++i)
      versions[i] = volume.brick_version(grid_position(static_cast<int64_t>(i), grid));
    dab_on_surface(volume, next, carve, 66.0f);
    carve = !carve;
    std::vector<int> coarse = full;
    for (size_t i = 0; i < versions.size(); ++i)
      if (versions[i] != volume.brick_version(grid_position(static_cast<int64_t>(i), grid)))
        coarse[i] = level;
    const auto t0 = std::chrono::steady_clock::now();
    coarse_meshed += static_cast<double>(cache.update(volume, coarse).bricks_meshed);
    const auto t1 = std::chrono::steady_clock::now();
    cache.update(volume, full);
    const auto t2 = std::chrono::steady_clock::now();
    coarse_s += std::chrono::duration<double>(t1 - t0).count();
    full_s += std::chrono::duration<double>(t2 - t1).count();
    state.SetIterationTime(std::chrono::duration<double>(t1 - t0).count());
  }
  const auto n = static_cast<double>(state.iterations());
  state.counters["coarse_ms"] = coarse_s / n * 1e3;
  state.counters["then_full_ms"] = full_s / n * 1e3;
  state.counters["coarse_bricks_meshed"] = coarse_meshed / n;
}
BENCHMARK(BM_MeshMixedLevelCoarseFirstAfterBigDab)
    ->Arg(1)
    ->Arg(2)
    ->ArgName("level")
    ->UseManualTime()
    ->Iterations(20)
    ->Unit(benchmark::kMillisecond);

// The window's simplifier on every brick of the 256^3 sphere at level 0 and
// the station's default bound (0.2 voxel); most of its time was the check
// that a result keeps the march's topology (check_topology, run twice a
// brick), measured alone in BM_CheckTopology.
const MeshCache& sphere_bricks(int n) {
  static std::map<int, std::unique_ptr<MeshCache>> caches;
  auto& c = caches[n];
  if (!c) {
    c = std::make_unique<MeshCache>(0, MarchingCubesOptions{127.5f, 0});
    c->update(sphere(n));
  }
  return *c;
}

std::vector<const BrickMesh*> non_empty_bricks(const MeshCache& cache) {
  std::vector<const BrickMesh*> bricks;
  const glm::ivec3 g = cache.brick_grid();
  for (int z = 0; z < g.z; ++z)
    for (int y = 0; y < g.y; ++y)
      for (int x = 0; x < g.x; ++x)
        if (const BrickMesh& b = cache.brick_mesh({x, y, z}); !b.mesh.triangles.empty())
          bricks.push_back(&b);
  return bricks;
}

// hold:0 holds the band of triangles around each brick's border (an
// export's chunks), hold:1 its vertices alone, hold:2 that and the window's
// limit on how far normals turn across a triangle (the drawn bricks; a
// sphere has no crease, so this is what checking the limit costs), hold:3
// the limit's places only counted (the refiner's quick pass, on the path
// to a new volume's full detail).
void BM_SimplifyBricks(benchmark::State& state) {
  const std::vector<const BrickMesh*> bricks = non_empty_bricks(sphere_bricks(256));
  const BorderHold hold = state.range(0) == 0 ? BorderHold::kBand : BorderHold::kVertices;
  // The window's limit: 37 degrees, in proportion less along edges longer
  // than 4 voxels, and 8 degrees between a removed vertex and the surface
  // made over it.
  NormalTurnLimit turn =
      state.range(0) >= 2 ? NormalTurnLimit{37.0f, 4.0f, 8.0f} : NormalTurnLimit{};
  if (state.range(0) == 3) turn.action = TurnLimit::kCount;
  int64_t kept = 0, marched = 0;
  for (auto _ : state) {
    kept = marched = 0;
    for (const BrickMesh* b : bricks) {
      const SimplifiedBrick s = simplify_brick_mesh(*b, 0.2f, hold, turn);
      kept += static_cast<int64_t>(s.brick.mesh.triangles.size());
      marched += static_cast<int64_t>(b->mesh.triangles.size());
    }
  }
  state.counters["bricks"] = static_cast<double>(bricks.size());
  state.counters["triangles_marched"] = static_cast<double>(marched);
  state.counters["triangles_kept"] = static_cast<double>(kept);
}
BENCHMARK(BM_SimplifyBricks)
    ->Arg(0)
    ->Arg(1)
    ->Arg(2)
    ->Arg(3)
    ->ArgName("hold")
    ->Unit(benchmark::kMillisecond);

// range(0) = 0: every brick's mesh checked on its own (as the simplifier
// does); 1: the whole sphere welded into one mesh (as an export is).
void BM_CheckTopology(benchmark::State& state) {
  const MeshCache& cache = sphere_bricks(256);
  const std::vector<const BrickMesh*> bricks = non_empty_bricks(cache);
  const Mesh welded = state.range(0) == 1 ? cache.welded_mesh() : Mesh{};
  int64_t edges = 0;
  for (auto _ : state) {
    edges = 0;
    if (state.range(0) == 1) {
      edges = check_topology(welded).edges;
    } else {
      for (const BrickMesh* b : bricks)
        edges += check_topology(b->mesh).edges;
    }
    benchmark::DoNotOptimize(edges);
  }
  state.counters["edges"] = static_cast<double>(edges);
}
BENCHMARK(BM_CheckTopology)->Arg(0)->Arg(1)->ArgName("welded")->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace sculpt::core
