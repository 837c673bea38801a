// A smoothing, inflating or pinching preview as the path grows (the
// station's ball-brush previews, station/app/brush_preview.h): the brush
// applied again to the whole path (range(1) = 0, what every preview did
// before) against brushing only what the path's newest segment reaches,
// reading the material before the stroke from a kept copy (range(1) = 1,
// *_stroke_part()). range(0): the path's samples so far, along a circle on
// the surface of the 256^3 peers.py sphere; range(2): the ball's radius, 8
// with samples 2 voxels apart (a small brush moved slowly) or 16 with
// samples 15 voxels apart (the bundled bust's nose smoothing, whose previews
// set its first-picture latency; 8 and 32 samples, a quarter turn and less
// than a whole one); each brush's default hardness, strength
// (smoothing: 4 blur passes; inflating: 1 voxel). Timed by hand around the brush call only
// (the volume's copy is set-up), on range(3) threads (1, and 2 for the
// bust's case: the material and the path's distances side by side).

#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>
#include <span>
#include <vector>

#include "sculpt/core/sculpt/inflate_brush.h"
#include "sculpt/core/sculpt/pinch_brush.h"
#include "sculpt/core/sculpt/smooth_brush.h"
#include "sculpt/core/shapes/analytic_shapes.h"
#include "sculpt/core/util/parallel_for.h"

namespace sculpt::core {
namespace {

template <class Options>
void brush_preview(benchmark::State& state,
                   int64_t (*whole)(Volume&, Sculptor&, std::span<const StrokeSample>,
                                    const Options&),
                   int64_t (*part_of)(Volume&, Sculptor&, std::span<const StrokeSample>,
                                      const Options&, const Box&, const Volume&)) {
  const auto samples = static_cast<size_t>(state.range(0));
  const bool extend = state.range(1) != 0;
  const auto ball_radius = static_cast<float>(state.range(2));
  const float spacing = ball_radius < 16.0f ? 2.0f : 15.0f;
  static const Volume* material = new Volume(sphere_volume(256, 0.35f));
  set_default_threads(static_cast<int>(state.range(3)));
  const glm::vec3 centre(127.5f);
  const float radius = 0.35f * 256.0f;
  std::vector<StrokeSample> path;
  for (size_t k = 0; k < samples; ++k) {
    const float a = spacing * static_cast<float>(k) / radius;
    path.push_back({centre + radius * glm::vec3(std::cos(a), std::sin(a), 0.0f),
                    glm::quat(1.0f, 0.0f, 0.0f, 0.0f)});
  }
  Options o;
  o.radius_vox = ball_radius;
  // The last preview, of the path but its newest sample.
  Volume shown = *material;
  {
    Sculptor s(shown);
    whole(shown, s, std::span(path).first(samples - 1), o);
  }
  // What the newest segment reaches (the station's box: radius + 2).
  const float reach = o.radius_vox + 2.0f;
  const glm::vec3 a = path[samples - 2].position_vox, b = path[samples - 1].position_vox;
  const Box part{glm::ivec3(glm::floor(glm::min(a, b) - reach)),
                 glm::ivec3(glm::ceil(glm::max(a, b) + reach)) + 1};
  int64_t changed = 0;
  for (auto _ : state) {
    Volume v = extend ? shown : *material;
    Sculptor s(v);
    const auto start = std::chrono::steady_clock::now();
    changed = extend ? part_of(v, s, path, o, part, *material) : whole(v, s, path, o);
    state.SetIterationTime(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  state.counters["voxels_changed"] = static_cast<double>(changed);
  set_default_threads(0);
}

void BM_SmoothPreview(benchmark::State& state) {
  brush_preview<SmoothBrushOptions>(state, smooth_stroke, smooth_stroke_part);
}
void BM_InflatePreview(benchmark::State& state) {
  brush_preview<InflateBrushOptions>(state, inflate_stroke, inflate_stroke_part);
}
void BM_PinchPreview(benchmark::State& state) {
  brush_preview<PinchBrushOptions>(state, pinch_stroke, pinch_stroke_part);
}
void preview_args(benchmark::internal::Benchmark* b) {
  for (int extend : {0, 1}) {
    for (int samples : {8, 32, 128})
      b->Args({samples, extend, 8, 1});
    for (int samples : {8, 32})
      b->Args({samples, extend, 16, 1});
  }
  // The bust's preview as the station makes it: its material and path
  // distances side by side on two threads.
  b->Args({8, 1, 16, 2});
}
BENCHMARK(BM_SmoothPreview)
    ->Apply(preview_args)
    ->ArgNames({"samples", "extend", "radius", "threads"})
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_InflatePreview)
    ->Apply(preview_args)
    ->ArgNames({"samples", "extend", "radius", "threads"})
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PinchPreview)
    ->Apply(preview_args)
    ->ArgNames({"samples", "extend", "radius", "threads"})
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace sculpt::core
