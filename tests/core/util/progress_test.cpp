// The progress and cancel callback through each long core function: a
// callback that cancels at its first report makes the call stop and say so;
// one that always continues changes no byte of the result; the fractions it
// sees never decrease and stay in [0, 1].

#include "sculpt/core/util/progress.h"

#include <gtest/gtest.h>

#include <atomic>
#include <cstring>
#include <functional>
#include <vector>

#include "sculpt/core/distance/iso_triangulation.h"
#include "sculpt/core/distance/mesh_distance.h"
#include "sculpt/core/distance/morphology.h"
#include "sculpt/core/distance/signed_distance.h"
#include "sculpt/core/grid/dense_grid.h"
#include "sculpt/core/mesh/mesh_cache.h"
#include "sculpt/core/shapes/analytic_shapes.h"
#include "sculpt/core/util/parallel_for.h"

namespace sculpt::core {
namespace {

// Records every fraction; cancels at report number `cancel_at` (0 = never).
struct Recorder {
  std::vector<double> fractions;
  int cancel_at = 0;
  Progress progress{[this](double f) {
    fractions.push_back(f);
    return cancel_at == 0 || int(fractions.size()) < cancel_at;
  }};
};

bool same_bytes(const DenseGrid<float>& a, const DenseGrid<float>& b) {
  return a.dims() == b.dims() &&
         std::memcmp(a.values().data(), b.values().data(), a.size() * sizeof(float)) == 0;
}

void expect_fractions_sane(const std::vector<double>& f) {
  ASSERT_FALSE(f.empty());
  for (size_t i = 0; i < f.size(); ++i) {
    EXPECT_GE(f[i], 0.0);
    EXPECT_LE(f[i], 1.0);
    if (i > 0) {
      EXPECT_GE(f[i], f[i - 1]) << "report " << i;
    }
  }
}

// The field-returning functions, each as one call taking a Progress*.
using FieldCall = std::function<DenseGrid<float>(Progress*)>;

void check_field_call(const FieldCall& call) {
  const DenseGrid<float> plain = call(nullptr);
  Recorder going;
  const DenseGrid<float> reported = call(&going.progress);
  EXPECT_FALSE(going.progress.cancelled());
  EXPECT_TRUE(going.progress.status().ok());
  EXPECT_TRUE(same_bytes(plain, reported));
  expect_fractions_sane(going.fractions);
  EXPECT_GT(going.fractions.size(), 2u);
  EXPECT_EQ(going.fractions.back(), 1.0);

  Recorder stopping;
  stopping.cancel_at = 1;
  call(&stopping.progress);
  EXPECT_TRUE(stopping.progress.cancelled());
  EXPECT_FALSE(stopping.progress.status().ok());
  EXPECT_EQ(stopping.fractions.size(), 1u) << "the callback is not called after it cancels";
}

DenseGrid<float> sphere_phi(int n) {
  return level_function(sphere_density(n));
}

TEST(Progress, ExactShellDistance) {
  const DenseGrid<float> phi = sphere_phi(40);
  check_field_call([&](Progress* p) {
    return signed_distance(phi, DistanceMethod::kExact, DistanceInit::kShell, 2, p);
  });
}

TEST(Progress, SurfaceDistanceForOffset) {
  const DenseGrid<float> phi = sphere_phi(36);
  check_field_call([&](Progress* p) { return surface_distance(phi, 2, p); });
}

TEST(Progress, Closing) {
  const DenseGrid<float> phi = sphere_phi(36);
  check_field_call([&](Progress* p) { return close_distance(phi, 3.0f, 2, p); });
}

Mesh sphere_mesh(int n) {
  const Volume volume = sphere_volume(n);
  MeshCache cache(0);
  cache.update(volume);
  return cache.welded_mesh();
}

TEST(Progress, Voxelize) {
  const Mesh mesh = sphere_mesh(32);
  const MeshDistance md(mesh);
  check_field_call([&](Progress* p) { return mesh_signed_distance(md, glm::ivec3(40), 2, p); });
}

TEST(Progress, WholeVolumeMesh) {
  const Volume volume = sphere_volume(128);
  MeshCache plain_cache(0, MarchingCubesOptions{127.5f, 2});
  plain_cache.update(volume);
  const Mesh plain = plain_cache.welded_mesh();

  Recorder going;
  MeshCache cache(0, MarchingCubesOptions{127.5f, 2});
  cache.update(volume, &going.progress);
  const Mesh reported = cache.welded_mesh();
  EXPECT_FALSE(going.progress.cancelled());
  EXPECT_EQ(plain.positions, reported.positions);
  EXPECT_EQ(plain.triangles, reported.triangles);
  expect_fractions_sane(going.fractions);
  EXPECT_GT(going.fractions.size(), 2u);

  // Cancelled at the first report, then updated again without progress: the
  // cache starts over and gives the full mesh.
  Recorder stopping;
  stopping.cancel_at = 1;
  MeshCache again(0, MarchingCubesOptions{127.5f, 2});
  again.update(volume, &stopping.progress);
  EXPECT_TRUE(stopping.progress.cancelled());
  EXPECT_EQ(stopping.fractions.size(), 1u);
  again.update(volume);
  EXPECT_EQ(again.welded_mesh().triangles, plain.triangles);
}

TEST(Progress, ReportsFromManyThreadsStayOrderedAndCountEveryUnit) {
  Recorder r;
  ProgressStage stage(&r.progress, 0.0, 1.0, 100000);
  std::atomic<int64_t> ran{0};
  parallel_for(
      100000, [&](int64_t) { ran.fetch_add(1); }, 4, stage);
  EXPECT_EQ(ran.load(), 100000);
  expect_fractions_sane(r.fractions);
  EXPECT_LE(r.fractions.size(), 1001u) << "rate-limited to a thousandth";
}

TEST(Progress, ACancelledStageSkipsTheRestOfTheLoop) {
  Progress p;
  p.cancel();
  ProgressStage stage(&p, 0.0, 1.0, 1000);
  std::atomic<int64_t> ran{0};
  parallel_for(
      1000, [&](int64_t) { ran.fetch_add(1); }, 4, stage);
  EXPECT_EQ(ran.load(), 0);
}

}  // namespace
}  // namespace sculpt::core
