// Wavelet volume benchmarks (issue: foundation). Workload: the peers.py sphere
// (../shared/bench/peers.py "haar"), 5 levels. Compare with
//   python3 ../shared/bench/peers.py haar --sizes 128,256
// run in the same session (tests/bench/compare_peers.py does both).

#include <benchmark/benchmark.h>

#include <cmath>

#include "sculpt/core/shapes/analytic_shapes.h"
#include "sculpt/core/util/parallel_for.h"
#include "sculpt/core/volume/volume.h"

namespace sculpt::core {
namespace {

VolumeOptions options_for(int threads) {
  VolumeOptions o;
  o.levels = 5;
  o.threads = threads;
  return o;
}

// Full decomposition of the dense n^3 sphere: every brick is visited; uniform
// bricks are detected and cost nothing more.
void BM_WaveletDecompose(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const int threads = static_cast<int>(state.range(1));
  const DenseGrid<uint8_t> sphere = sphere_density(n);
  for (auto _ : state) {
    Volume v = Volume::from_dense(sphere, options_for(threads));
    benchmark::DoNotOptimize(v);
  }
  state.counters["threads"] = threads == 0 ? hardware_threads() : threads;
  state.SetItemsProcessed(state.iterations() * int64_t{n} * n * n);
}
BENCHMARK(BM_WaveletDecompose)->ArgsProduct({{128, 256}, {1, 0}})->Unit(benchmark::kMillisecond);

// The same transforms with no uniform shortcut: every brick of a noise volume
// holds detail, the worst case for the encoder (pywt's cost does not depend on
// the content, ours does).
DenseGrid<uint8_t> noise_volume(int n) {
  DenseGrid<uint8_t> noise{glm::ivec3(n)};
  uint32_t s = 12345;
  for (uint8_t& v : noise.values()) {
    s = s * 1664525u + 1013904223u;
    v = static_cast<uint8_t>(s >> 24);
  }
  return noise;
}

void BM_WaveletDecomposeNoise(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const DenseGrid<uint8_t> noise = noise_volume(n);
  for (auto _ : state) {
    Volume v = Volume::from_dense(noise, options_for(static_cast<int>(state.range(1))));
    benchmark::DoNotOptimize(v);
  }
  state.SetItemsProcessed(state.iterations() * int64_t{n} * n * n);
}
BENCHMARK(BM_WaveletDecomposeNoise)->ArgsProduct({{256}, {1, 0}})->Unit(benchmark::kMillisecond);

void BM_WaveletReconstructNoise(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const Volume v =
      Volume::from_dense(noise_volume(n), options_for(static_cast<int>(state.range(1))));
  for (auto _ : state) {
    DenseGrid<uint8_t> out = v.to_dense(0);
    benchmark::DoNotOptimize(out);
  }
  state.SetItemsProcessed(state.iterations() * int64_t{n} * n * n);
}
BENCHMARK(BM_WaveletReconstructNoise)->ArgsProduct({{256}, {1, 0}})->Unit(benchmark::kMillisecond);

// Full reconstruction of level 0 into a dense array.
void BM_WaveletReconstruct(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const int threads = static_cast<int>(state.range(1));
  const Volume v = Volume::from_dense(sphere_density(n), options_for(threads));
  for (auto _ : state) {
    DenseGrid<uint8_t> out = v.to_dense(0);
    benchmark::DoNotOptimize(out);
  }
  state.SetItemsProcessed(state.iterations() * int64_t{n} * n * n);
}
BENCHMARK(BM_WaveletReconstruct)->ArgsProduct({{128, 256}, {1, 0}})->Unit(benchmark::kMillisecond);

// Extraction of level k of the 128^3 volume (the paper's Table 1, right part).
void BM_WaveletExtractLevel(benchmark::State& state) {
  const int level = static_cast<int>(state.range(0));
  const Volume v = Volume::from_dense(sphere_density(128), options_for(1));
  for (auto _ : state) {
    DenseGrid<uint8_t> out = v.to_dense(level);
    benchmark::DoNotOptimize(out);
  }
}
BENCHMARK(BM_WaveletExtractLevel)->DenseRange(0, 3)->Unit(benchmark::kMicrosecond);

// Re-encoding after a 32^3 edit on the surface of the 256^3 sphere: the edit
// straddles brick boundaries, so it touches 8 bricks, and only those are
// decoded and re-encoded.
void BM_WaveletReencodeEdit(benchmark::State& state) {
  Volume v = sphere_volume(256, 0.35f, options_for(1));
  const int corner = static_cast<int>(127.5f + 0.35f * 256.0f / std::sqrt(3.0f)) - 16;
  const Box box{glm::ivec3(corner), glm::ivec3(corner + 32)};
  uint8_t delta = 0;
  int64_t touched = 0;
  for (auto _ : state) {
    const auto flip = static_cast<uint8_t>(++delta & 1);  // a copy: no aliasing with the voxels
    v.edit(box, [flip](glm::ivec3, std::span<uint8_t> voxels) {
      for (uint8_t& x : voxels)
        x = static_cast<uint8_t>(x ^ flip);
    });
    touched = static_cast<int64_t>(v.take_dirty_bricks().size());
  }
  state.counters["bricks_touched"] = static_cast<double>(touched);
}
BENCHMARK(BM_WaveletReencodeEdit)->Unit(benchmark::kMicrosecond);

// Memory of a 1024^3 volume holding the sphere, built brick by brick.
void BM_WaveletMemory1024(benchmark::State& state) {
  VolumeStats s;
  for (auto _ : state) {
    const Volume v = sphere_volume(1024, 0.35f, options_for(0));
    s = v.stats();
  }
  state.counters["memory_MiB"] = static_cast<double>(s.memory_bytes) / (1 << 20);
  state.counters["memory_bytes"] = static_cast<double>(s.memory_bytes);
  state.counters["detailed_bricks"] = static_cast<double>(s.bricks - s.uniform_bricks);
}
BENCHMARK(BM_WaveletMemory1024)->Iterations(1)->Unit(benchmark::kMillisecond);

// One 32^3 brick of noise through the pyramid alone: the kernel's cost
// without allocation or uniform detection.
void BM_PyramidEncodeBrick(benchmark::State& state) {
  std::vector<uint8_t> voxels = noise_volume(32).values();
  WaveletPyramid p(32, 5);
  for (auto _ : state) {
    p.encode(voxels);
    benchmark::DoNotOptimize(p.coefficients().data());
  }
  state.SetItemsProcessed(state.iterations() * 32 * 32 * 32);
}
BENCHMARK(BM_PyramidEncodeBrick)->Unit(benchmark::kMicrosecond);

void BM_PyramidDecodeBrick(benchmark::State& state) {
  std::vector<uint8_t> voxels = noise_volume(32).values();
  WaveletPyramid p(32, 5);
  p.encode(voxels);
  for (auto _ : state) {
    p.decode(voxels);
    benchmark::DoNotOptimize(voxels.data());
  }
  state.SetItemsProcessed(state.iterations() * 32 * 32 * 32);
}
BENCHMARK(BM_PyramidDecodeBrick)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace sculpt::core
