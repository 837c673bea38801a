// The brushes a grown preview extends (smooth, inflate, pinch): brushing a
// path part by part, each part reading the material from before the
// stroke, leaves exactly what brushing it whole does, and nothing outside
// the part is touched. The material varies along the parts' seam (a bumpy
// slab), so a part that read too little around it would differ.

#include <gtest/gtest.h>

#include <functional>
#include <string>
#include <vector>

#include "brush_test_shapes.h"
#include "sculpt/core/sculpt/inflate_brush.h"
#include "sculpt/core/sculpt/pinch_brush.h"
#include "sculpt/core/sculpt/sculptor.h"
#include "sculpt/core/sculpt/smooth_brush.h"

namespace sculpt::core {
namespace {

using Part = std::function<int64_t(Volume&, Sculptor&, std::span<const StrokeSample>,
                                   const Box& part, const Volume& before)>;

int64_t voxels_differing(const Volume& a, const Volume& b, const Box& within) {
  int64_t n = 0;
  for (int z = within.lo.z; z < within.hi.z; ++z)
    for (int y = within.lo.y; y < within.hi.y; ++y)
      for (int x = within.lo.x; x < within.hi.x; ++x)
        n += a.voxel({x, y, z}) != b.voxel({x, y, z});
  return n;
}

TEST(BrushParts, BrushedPartByPartIsBrushedWhole) {
  SmoothBrushOptions smooth;
  smooth.radius_vox = 7.0f;
  smooth.strength = 1.0f;
  InflateBrushOptions inflate;
  inflate.radius_vox = 7.0f;
  inflate.distance_vox = 3.0f;
  PinchBrushOptions pinch;
  pinch.radius_vox = 7.0f;
  pinch.strength = 1.0f;
  const std::pair<std::string, Part> kBrushes[] = {
      {"smooth",
       [&](Volume& v, Sculptor& s, auto path, const Box& part, const Volume& before) {
         return smooth_stroke_part(v, s, path, smooth, part, before);
       }},
      {"inflate",
       [&](Volume& v, Sculptor& s, auto path, const Box& part, const Volume& before) {
         return inflate_stroke_part(v, s, path, inflate, part, before);
       }},
      {"pinch",
       [&](Volume& v, Sculptor& s, auto path, const Box& part, const Volume& before) {
         return pinch_stroke_part(v, s, path, pinch, part, before);
       }},
  };
  // Along x over the bumps, dipping into them.
  std::vector<StrokeSample> path;
  for (float x = 16.0f; x <= 48.0f; x += 2.0f)
    path.push_back({{x, 30.0f + 0.2f * (x - 16.0f), test::kSlabTop}, {}});
  const Volume material = test::bumpy_slab(3.0f);
  const Box all{glm::ivec3(0), material.dims()};
  // Split across the path's middle, where it writes most.
  const Box first{glm::ivec3(0), {31, test::kSlabN, test::kSlabN}};
  const Box second{{31, 0, 0}, material.dims()};

  for (const auto& [name, brush] : kBrushes) {
    Volume whole = material;
    Sculptor whole_sculptor(whole);
    ASSERT_GT(brush(whole, whole_sculptor, path, all, whole), 1000) << name;

    Volume parts = material;
    Sculptor sculptor(parts);
    EXPECT_GT(brush(parts, sculptor, path, first, material), 0) << name;
    EXPECT_EQ(voxels_differing(parts, material, second), 0) << name << ": the first part only";
    EXPECT_EQ(voxels_differing(parts, whole, first), 0) << name;
    EXPECT_GT(brush(parts, sculptor, path, second, material), 0) << name;
    EXPECT_EQ(voxels_differing(parts, whole, all), 0) << name;
  }
}

}  // namespace
}  // namespace sculpt::core
