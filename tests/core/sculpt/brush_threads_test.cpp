// Every ball brush leaves the same volume on one core and on several: the
// material and the path's distances are made side by side and the write
// runs slices of the box on every core (brush_field.h), and recordings
// replay bit for bit only if neither changes a voxel. The default brushes
// (hardness, strength) on the bumpy slab, along a path that turns.

#include <gtest/gtest.h>

#include <functional>
#include <string>
#include <vector>

#include "brush_test_shapes.h"
#include "sculpt/core/sculpt/clay_brush.h"
#include "sculpt/core/sculpt/flatten_brush.h"
#include "sculpt/core/sculpt/grab_brush.h"
#include "sculpt/core/sculpt/inflate_brush.h"
#include "sculpt/core/sculpt/pinch_brush.h"
#include "sculpt/core/sculpt/sculptor.h"
#include "sculpt/core/sculpt/smooth_brush.h"
#include "sculpt/core/util/parallel_for.h"

namespace sculpt::core {
namespace {

using Brush = std::function<int64_t(Volume&, Sculptor&, std::span<const StrokeSample>)>;

template <class Options>
Options ball(float radius) {
  Options o;
  o.radius_vox = radius;
  return o;
}

TEST(BrushThreads, EveryBallBrushIsTheSameOnOneCoreAndOnThree) {
  const std::pair<std::string, Brush> kBrushes[] = {
      {"smooth", [](Volume& v, Sculptor& s,
                    auto p) { return smooth_stroke(v, s, p, ball<SmoothBrushOptions>(9.0f)); }},
      {"inflate", [](Volume& v, Sculptor& s,
                     auto p) { return inflate_stroke(v, s, p, ball<InflateBrushOptions>(9.0f)); }},
      {"pinch", [](Volume& v, Sculptor& s,
                   auto p) { return pinch_stroke(v, s, p, ball<PinchBrushOptions>(9.0f)); }},
      {"clay", [](Volume& v, Sculptor& s,
                  auto p) { return clay_stroke(v, s, p, ball<ClayBrushOptions>(9.0f)); }},
      {"flatten", [](Volume& v, Sculptor& s,
                     auto p) { return flatten_stroke(v, s, p, ball<FlattenBrushOptions>(9.0f)); }},
      {"grab", [](Volume& v, Sculptor& s,
                  auto p) { return grab_stroke(v, s, p, ball<GrabBrushOptions>(9.0f)); }},
  };
  std::vector<StrokeSample> path;
  for (float t = 0.0f; t <= 1.0f; t += 0.0625f)
    path.push_back({{14.0f + 36.0f * t, 24.0f + 16.0f * t * t, test::kSlabTop + 1.5f}, {}});
  const Volume material = test::bumpy_slab(3.0f);
  for (const auto& entry : kBrushes) {
    const std::string& name = entry.first;
    const Brush& brush = entry.second;
    auto run = [&](int threads) {
      set_default_threads(threads);
      Volume v = material;
      Sculptor s(v);
      const int64_t changed = brush(v, s, path);
      set_default_threads(0);
      EXPECT_GT(changed, 200) << name;
      return v.content_hash();
    };
    const uint64_t one = run(1);
    EXPECT_NE(one, material.content_hash()) << name;
    EXPECT_EQ(run(3), one) << name;
  }
}

}  // namespace
}  // namespace sculpt::core
