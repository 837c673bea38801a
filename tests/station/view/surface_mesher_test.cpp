#include "sculpt/station/view/surface_mesher.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <memory>
#include <random>
#include <thread>
#include <vector>

#include "sculpt/core/mesh/brick_simplify.h"
#include "sculpt/core/mesh/mixed_level_mesh.h"
#include "sculpt/core/sculpt/sculptor.h"
#include "sculpt/core/shapes/analytic_shapes.h"
#include "sculpt/core/tool/tool.h"
#include "sculpt/hal/types/clock.h"
#include "sculpt/sim/synth/bundled_sessions.h"
#include "sculpt/station/app/session_loading.h"
#include "sculpt/station/app/session_replay.h"
#include "sculpt/station/app/station_loop.h"
#include "sculpt/station/view/lod_selector.h"

namespace sculpt::station {
namespace {

// Per-brick levels that vary across the grid, as a camera's LOD gives them.
std::vector<int> levels_for(const core::Volume& v, int shift) {
  std::vector<int> levels(static_cast<size_t>(v.brick_count()));
  for (size_t i = 0; i < levels.size(); ++i)
    levels[i] = static_cast<int>((i + static_cast<size_t>(shift)) % 3);
  return levels;
}

// The surface a snapshot holds equals the one meshed from scratch: every
// brick's mesh, brick by brick, simplified as the mesher does: within
// turn_limit(), or, for a brick a new volume's refinement simplified
// quickly, as quickly when no triangle made there turns too far (the quick
// pass does not look at the vertices it removed).
void expect_same_surface(const SurfaceSnapshot& snapshot, const core::Volume& volume,
                         const std::vector<int>& levels,
                         float simplify_error = SurfaceMesher::kSimplifyError) {
  core::MixedLevelMeshCache scratch;
  scratch.update(volume, levels);
  int64_t non_empty = 0;
  for (int64_t i = 0; i < volume.brick_count(); ++i) {
    const glm::ivec3 b = core::grid_position(i, volume.brick_grid());
    const core::BrickMesh& want = scratch.brick_mesh(b);
    const auto it = snapshot.bricks().find(i);
    if (want.empty()) {
      EXPECT_TRUE(it == snapshot.bricks().end()) << "brick " << i;
      continue;
    }
    ++non_empty;
    ASSERT_TRUE(it != snapshot.bricks().end()) << "brick " << i;
    EXPECT_EQ(it->second.level, levels[static_cast<size_t>(i)]);
    const int level = levels[static_cast<size_t>(i)];
    const float error = simplify_error * static_cast<float>(1 << level);
    const core::SimplifiedBrick held = core::simplify_brick_mesh(
        want, error, core::BorderHold::kVertices, SurfaceMesher::turn_limit(level));
    const core::SimplifiedBrick quick = core::simplify_brick_mesh(
        want, error, core::BorderHold::kVertices, SurfaceMesher::quick_turn_limit(level));
    const core::Mesh& shown = it->second.mesh->mesh;
    EXPECT_TRUE(shown == held.brick.mesh || (quick.turning == 0 && shown == quick.brick.mesh))
        << "brick " << i;
  }
  EXPECT_GT(non_empty, 8);
  EXPECT_EQ(static_cast<int64_t>(snapshot.bricks().size()), non_empty);
}

class Sculpting {
 public:
  explicit Sculpting(int n, uint32_t seed)
      : volume_(std::make_unique<core::Volume>(core::Volume::from_dense(
            core::sphere_density(n), core::VolumeOptions{.brick_edge = 8, .levels = 3}))),
        random_(seed) {
    sculptor_ = std::make_unique<core::Sculptor>(*volume_);
    sculptor_->set_tool(core::make_sphere_tool(3.0f));
  }
  void dab() {
    std::uniform_real_distribution<float> at(8.0f, static_cast<float>(volume_->dims().x) - 8.0f);
    core::Dab d;
    d.position_vox = {at(random_), at(random_), at(random_)};
    d.mode = random_() % 2 ? core::SculptMode::kAdd : core::SculptMode::kSubtract;
    sculptor_->dab(d);
  }
  void replace(int n) {
    sculptor_.reset();
    volume_ = std::make_unique<core::Volume>(core::Volume::from_dense(
        core::sphere_density(n), core::VolumeOptions{.brick_edge = 8, .levels = 3}));
    sculptor_ = std::make_unique<core::Sculptor>(*volume_);
    sculptor_->set_tool(core::make_sphere_tool(2.5f));
    ++generation_;
  }
  /// Stores every brick again with the voxels it has.
  void store_again() {
    volume_->edit(core::Box{glm::ivec3(0), volume_->dims()}, [](glm::ivec3, std::span<uint8_t>) {});
  }
  const core::Volume& volume() const { return *volume_; }
  uint64_t generation() const { return generation_; }

 private:
  std::unique_ptr<core::Volume> volume_;
  std::unique_ptr<core::Sculptor> sculptor_;
  std::mt19937 random_;
  uint64_t generation_ = 1;
};

void deltas_build_the_surface_meshed_from_scratch(float simplify_error) {
  Sculpting s(64, 7);
  SurfaceMesher mesher(0, simplify_error);
  SurfaceSnapshot snapshot;
  std::vector<int> levels = levels_for(s.volume(), 0);
  uint64_t last = mesher.submit(s.volume(), s.generation(), levels);
  for (int step = 0; step < 60; ++step) {
    for (int d = 0; d < 1 + step % 3; ++d)
      s.dab();
    if (step == 5 || step == 12) levels = levels_for(s.volume(), step);  // the camera moved
    if (step == 20) {  // a project opened: another volume
      s.replace(48);
      levels = levels_for(s.volume(), 1);
    }
    const uint64_t change = mesher.submit(s.volume(), s.generation(), levels);
    EXPECT_GE(change, last);
    last = change;
    // Meshed before the next change half the time, taken every third step:
    // deltas not taken yet are merged.
    if (step % 2 == 0) mesher.wait_until_meshed();
    if (step % 3 == 0)
      if (auto delta = mesher.take()) snapshot.apply(std::move(*delta));
  }
  mesher.wait_until_meshed();
  auto delta = mesher.take();
  ASSERT_TRUE(delta.has_value());
  EXPECT_EQ(delta->change, last);
  snapshot.apply(std::move(*delta));
  expect_same_surface(snapshot, s.volume(), levels, simplify_error);
  const MesherCounters c = mesher.counters();
  EXPECT_GT(c.bricks_submitted, 0);
  EXPECT_LE(c.updates, c.submits);
  EXPECT_EQ(c.update_us.count(), c.updates);
  if (simplify_error > 0) {
    EXPECT_GT(c.bricks_simplified, 0);
    EXPECT_GT(c.simplify_queue_max, 0);
    EXPECT_LE(c.simplify_queue_max, 8 * 8 * 8);  // one job per brick of the bigger volume at most
    EXPECT_LT(c.triangles_kept, c.triangles_marched);
    EXPECT_LE(c.simplify_error_max, 4 * simplify_error);  // level 2 bricks: 4 times
  } else {
    EXPECT_EQ(c.bricks_simplified, 0);
  }
}

TEST(SurfaceMesher, DeltasBuildTheSurfaceMeshedFromScratch) {
  deltas_build_the_surface_meshed_from_scratch(SurfaceMesher::kSimplifyError);
}

TEST(SurfaceMesher, DeltasBuildTheMarchedSurfaceWhenNotSimplifying) {
  deltas_build_the_surface_meshed_from_scratch(0.0f);
}

TEST(SurfaceMesher, ANewVolumeIsShownCoarseFirstThenAtFullDetail) {
  Sculpting s(64, 5);
  SurfaceMesher mesher;
  const std::vector<int> full(static_cast<size_t>(s.volume().brick_count()), 0);
  const uint64_t change = mesher.submit(s.volume(), s.generation(), full);
  mesher.wait_until_meshed();
  const auto delta = mesher.take();
  ASSERT_TRUE(delta.has_value());
  EXPECT_TRUE(delta->reset);
  EXPECT_EQ(delta->change, change);
  EXPECT_EQ(delta->full_detail_change, change);
  EXPECT_EQ(mesher.counters().coarse_first, 1);
  for (const BrickSurface& b : delta->bricks)
    EXPECT_EQ(b.level, 0);  // the coarse meshes were replaced by the full ones
  // A dab is not a new volume: straight to full detail.
  s.dab();
  mesher.submit(s.volume(), s.generation(), full);
  mesher.wait_until_meshed();
  EXPECT_EQ(mesher.counters().coarse_first, 1);
}

// Waits for the mesher to publish `change` (the test's own polling: no
// timing is asserted) and folds what it published into the snapshot.
SurfaceDelta take_change(SurfaceMesher& mesher, SurfaceSnapshot& snapshot, uint64_t change) {
  SurfaceDelta last;
  while (last.change < change) {
    if (std::optional<SurfaceDelta> delta = mesher.take()) {
      last.change = delta->change;
      last.full_detail_change = delta->full_detail_change;
      for (const BrickSurface& b : delta->bricks)
        last.bricks.push_back(b);
      snapshot.apply(std::move(*delta));
    } else {
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
  }
  return last;
}

// While a new volume is refined, the dabs on it are shown at once at the
// coarse level; the refined meshes then replace every coarse one, dabs
// included, and the surface is the one meshed from scratch at full detail.
TEST(SurfaceMesher, DabsOnANewVolumeAreShownCoarseWhileItIsRefined) {
  Sculpting s(64, 9);
  SurfaceMesher mesher;
  SurfaceSnapshot snapshot;
  const std::vector<int> full(static_cast<size_t>(s.volume().brick_count()), 0);
  mesher.hold_refinement(true);
  const uint64_t first = mesher.submit(s.volume(), s.generation(), full);
  const SurfaceDelta coarse = take_change(mesher, snapshot, first);
  EXPECT_LT(coarse.full_detail_change, first);
  ASSERT_FALSE(coarse.bricks.empty());
  for (const BrickSurface& b : coarse.bricks)
    EXPECT_EQ(b.level, 2);
  uint64_t previous = first;
  for (int d = 0; d < 6; ++d) {
    s.dab();
    const uint64_t change = mesher.submit(s.volume(), s.generation(), full);
    if (change == previous) continue;  // the dab changed nothing
    previous = change;
    const SurfaceDelta dab = take_change(mesher, snapshot, change);
    EXPECT_LT(dab.full_detail_change, first);
    for (const BrickSurface& b : dab.bricks)
      EXPECT_EQ(b.level, 2) << "dab " << d << ", brick " << b.index;
  }
  EXPECT_GT(previous, first);
  // The mesher counts an update just after publishing it: the new volume's
  // and each dab's, one each (each change was taken before the next).
  const auto updates = static_cast<int64_t>(1 + previous - first);
  while (mesher.counters().updates < updates)
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  EXPECT_EQ(mesher.counters().coarse_updates, static_cast<int64_t>(previous - first));
  EXPECT_EQ(mesher.counters().refinements, 0);
  mesher.hold_refinement(false);
  mesher.wait_until_meshed();
  const auto last = mesher.take();
  ASSERT_TRUE(last.has_value());
  EXPECT_TRUE(last->reset);
  EXPECT_EQ(last->full_detail_change, last->change);
  for (const BrickSurface& b : last->bricks)
    EXPECT_TRUE(b.simplified) << "brick " << b.index;  // by the refiner, then the simplifier
  snapshot.apply(*last);
  expect_same_surface(snapshot, s.volume(), full);
  const MesherCounters c = mesher.counters();
  EXPECT_EQ(c.refinements, 1);
  EXPECT_GE(c.refine_passes, 1);
  EXPECT_EQ(c.refine_us.count(), c.refine_passes);
  // The refiner's quick simplifications that made a triangle turning
  // further than the limit, simplified again from the march with it
  // (expect_same_surface checks them); the others were right as they were.
  core::MixedLevelMeshCache scratch;
  scratch.update(s.volume(), full);
  int64_t turning = 0, non_empty = 0;
  for (int64_t i = 0; i < s.volume().brick_count(); ++i) {
    const core::BrickMesh& m = scratch.brick_mesh(core::grid_position(i, s.volume().brick_grid()));
    if (m.empty()) continue;
    ++non_empty;
    turning +=
        core::simplify_brick_mesh(m, SurfaceMesher::kSimplifyError, core::BorderHold::kVertices,
                                  SurfaceMesher::quick_turn_limit(0))
            .turning > 0;
  }
  EXPECT_GT(turning, 0);
  EXPECT_LT(turning, non_empty);
  EXPECT_EQ(c.bricks_polished, turning);
}

// The refiner makes one pass over a new volume, however many dabs come
// during and after it; the mesher meshes those itself when it takes the
// pass over, at full detail, and the surface is the one meshed from scratch.
TEST(SurfaceMesher, TheRefinerMakesOnePassAndTheMesherCatchesUp) {
  Sculpting s(64, 11);
  SurfaceMesher mesher;
  SurfaceSnapshot snapshot;
  const std::vector<int> full(static_cast<size_t>(s.volume().brick_count()), 0);
  mesher.hold_take_over(true);
  const uint64_t first = mesher.submit(s.volume(), s.generation(), full);
  take_change(mesher, snapshot, first);
  while (mesher.counters().refine_passes < 1)
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  // Dabs after the pass: meshed coarse at once, waiting for the take-over.
  uint64_t last = first;
  for (int d = 0; d < 6; ++d) {
    s.dab();
    last = mesher.submit(s.volume(), s.generation(), full);
    const SurfaceDelta dab = take_change(mesher, snapshot, last);
    EXPECT_LT(dab.full_detail_change, first);
  }
  EXPECT_GT(last, first);
  EXPECT_EQ(mesher.counters().refine_passes, 1);
  EXPECT_EQ(mesher.counters().refinements, 0);
  mesher.hold_take_over(false);
  mesher.wait_until_meshed();
  while (std::optional<SurfaceDelta> delta = mesher.take()) {
    EXPECT_EQ(delta->full_detail_change, last);
    snapshot.apply(std::move(*delta));
  }
  expect_same_surface(snapshot, s.volume(), full);
  const MesherCounters c = mesher.counters();
  EXPECT_EQ(c.refine_passes, 1);
  EXPECT_EQ(c.refinements, 1);
}

// A newer volume abandons the refinement of the one before: only the newer
// one's refined meshes are taken over.
TEST(SurfaceMesher, ANewerVolumeAbandonsTheRefinementUnderWay) {
  Sculpting s(64, 4);
  SurfaceMesher mesher;
  SurfaceSnapshot snapshot;
  mesher.hold_refinement(true);
  const std::vector<int> full64(static_cast<size_t>(s.volume().brick_count()), 0);
  take_change(mesher, snapshot, mesher.submit(s.volume(), s.generation(), full64));
  s.replace(48);
  const std::vector<int> full48(static_cast<size_t>(s.volume().brick_count()), 0);
  take_change(mesher, snapshot, mesher.submit(s.volume(), s.generation(), full48));
  mesher.hold_refinement(false);
  mesher.wait_until_meshed();
  while (std::optional<SurfaceDelta> delta = mesher.take())
    snapshot.apply(std::move(*delta));
  expect_same_surface(snapshot, s.volume(), full48);
  EXPECT_EQ(mesher.counters().refinements, 1);
  EXPECT_EQ(mesher.counters().coarse_first, 2);
}

// The window's own sequence: the demo played through the station loop (a
// new volume, a head, dabs of every size), the mesher fed after every
// sample at the levels a camera would pick, taken now and then.
TEST(SurfaceMesher, ThePlayedDemoEndsOnTheSurfaceMeshedFromScratch) {
  auto session = load_session(sim::bundled_session_path("demo"));
  ASSERT_TRUE(session.ok());
  StationLoop::Options o;
  o.mesh = false;
  o.clay_margin = 64;  // the window's first block
  StationLoop loop(o);
  SurfaceMesher mesher;
  SurfaceSnapshot snapshot;
  LodSelector lod;
  const glm::vec3 eye(128.0f, 128.0f, -400.0f);
  std::vector<int> levels;
  int samples = 0;
  auto feed = [&] {
    const core::Volume& v = loop.volume();
    levels = lod.select(v.brick_grid(), v.brick_edge(), eye, 300.0f);
    mesher.submit(v, loop.volume_generation(), levels);
    if (++samples % 5 == 0)
      if (auto delta = mesher.take()) snapshot.apply(std::move(*delta));
  };
  feed();
  ReplayOptions options;
  options.fast = true;
  options.on_sample = [&](const hal::InputEvent&) { feed(); };
  ASSERT_TRUE(replay_session(*session, "demo", loop, options).ok());
  feed();
  mesher.wait_until_meshed();
  if (auto delta = mesher.take()) snapshot.apply(std::move(*delta));
  EXPECT_GT(snapshot.triangle_count(), 10000);
  expect_same_surface(snapshot, loop.volume(), levels);
  // Each new volume (the window's block, then the session's) was refined
  // in one pass at most, however many dabs came during it: the mesher
  // meshed those itself when it took the pass over.
  const MesherCounters c = mesher.counters();
  EXPECT_EQ(c.refinements, 1);
  EXPECT_LE(c.refine_passes, c.coarse_first);
  // Simplified brick by brick, at the levels the camera gave, the bricks
  // still meet without a crack: welded, no edge is open. (Only their border
  // vertices are held, so two bricks may share an edge between two of them:
  // four triangles, which a renderer drawing them one by one never sees.)
  std::vector<const core::BrickMesh*> parts;
  for (const auto& [index, brick] : snapshot.bricks())
    parts.push_back(brick.mesh.get());
  const core::MeshTopology t = core::check_topology(core::weld_brick_meshes(parts));
  EXPECT_EQ(t.boundary_edges, 0);
  EXPECT_EQ(t.misoriented_edges, 0);
}

TEST(SurfaceMesher, NothingChangedIsNoChange) {
  Sculpting s(48, 3);
  SurfaceMesher mesher;
  const std::vector<int> levels = levels_for(s.volume(), 0);
  const uint64_t first = mesher.submit(s.volume(), s.generation(), levels);
  EXPECT_EQ(mesher.submit(s.volume(), s.generation(), levels), first);
  s.dab();
  EXPECT_EQ(mesher.submit(s.volume(), s.generation(), levels), first + 1);
  mesher.wait_until_meshed();
  EXPECT_EQ(mesher.counters().submits, 2);
}

// The window counts a dab handed over when its change is queued (the
// slowest dabs' split in --stats), which submit() says only when it queues.
TEST(SurfaceMesher, SubmitSaysWhenItQueuedAChange) {
  Sculpting s(48, 3);
  SurfaceMesher mesher;
  const std::vector<int> levels = levels_for(s.volume(), 0);
  int64_t queued_ns = -1;
  const int64_t before = hal::monotonic_ns();
  mesher.submit(s.volume(), s.generation(), levels, &queued_ns);
  const int64_t after = hal::monotonic_ns();
  EXPECT_TRUE(queued_ns >= before && queued_ns <= after) << before << " " << queued_ns;
  queued_ns = -1;
  mesher.submit(s.volume(), s.generation(), levels, &queued_ns);
  EXPECT_EQ(queued_ns, -1);  // nothing changed: nothing queued
  s.dab();
  mesher.submit(s.volume(), s.generation(), levels, &queued_ns);
  EXPECT_GE(queued_ns, after);
  mesher.wait_until_meshed();
}

TEST(SurfaceMesher, BricksStoredAgainUnchangedAreNotMeshedAgain) {
  Sculpting s(48, 4);
  SurfaceMesher mesher(0, 0.0f);
  SurfaceSnapshot snapshot;
  const std::vector<int> levels = levels_for(s.volume(), 0);
  mesher.submit(s.volume(), s.generation(), levels);
  mesher.wait_until_meshed();
  const int64_t meshed = mesher.counters().bricks_meshed;
  s.store_again();
  mesher.submit(s.volume(), s.generation(), levels);
  mesher.wait_until_meshed();
  EXPECT_EQ(mesher.counters().bricks_unchanged, s.volume().brick_count());
  EXPECT_EQ(mesher.counters().bricks_meshed, meshed);
  s.store_again();
  s.dab();
  mesher.submit(s.volume(), s.generation(), levels);
  mesher.wait_until_meshed();
  EXPECT_GT(mesher.counters().bricks_meshed, meshed);
  EXPECT_GT(mesher.counters().bricks_unchanged, s.volume().brick_count());
  while (std::optional<SurfaceDelta> delta = mesher.take())
    snapshot.apply(std::move(*delta));
  expect_same_surface(snapshot, s.volume(), levels, 0.0f);
}

TEST(SurfaceMesher, ZoomingOutAndBackInMeshesNoBrickTwice) {
  // The camera's levels move away and come back with the volume unchanged:
  // the second move gives the bricks their earlier meshes back, and what the
  // renderer holds is still the surface meshed from scratch.
  Sculpting s(64, 5);
  SurfaceMesher mesher(0, 0.0f);
  SurfaceSnapshot snapshot;
  const std::vector<int> near = levels_for(s.volume(), 0);
  const std::vector<int> far = levels_for(s.volume(), 1);
  for (const std::vector<int>* levels : {&near, &far}) {
    mesher.submit(s.volume(), s.generation(), *levels);
    mesher.wait_until_meshed();
  }
  const int64_t meshed = mesher.counters().bricks_meshed;
  EXPECT_EQ(mesher.counters().bricks_reused, 0);
  mesher.submit(s.volume(), s.generation(), near);
  mesher.wait_until_meshed();
  EXPECT_EQ(mesher.counters().bricks_meshed, meshed);
  EXPECT_GT(mesher.counters().bricks_reused, 0);
  while (std::optional<SurfaceDelta> delta = mesher.take())
    snapshot.apply(std::move(*delta));
  expect_same_surface(snapshot, s.volume(), near, 0.0f);
}

// Sculpting and drawing threads hammer the mesher as the window does; run
// under ThreadSanitizer in CI. The end state must still be exact.
TEST(SurfaceMesher, ConcurrentSubmitAndTakeEndOnTheExactSurface) {
  Sculpting s(64, 11);
  SurfaceMesher mesher;
  const std::vector<int> levels = levels_for(s.volume(), 2);
  std::atomic<bool> done{false};
  SurfaceSnapshot snapshot;
  std::thread drawer([&] {
    while (!done.load()) {
      if (auto delta = mesher.take()) snapshot.apply(std::move(*delta));
      std::this_thread::yield();
    }
  });
  for (int step = 0; step < 150; ++step) {
    s.dab();
    mesher.submit(s.volume(), s.generation(), levels);
  }
  mesher.wait_until_meshed();
  done = true;
  drawer.join();
  if (auto delta = mesher.take()) snapshot.apply(std::move(*delta));
  expect_same_surface(snapshot, s.volume(), levels);
  const MesherCounters c = mesher.counters();
  EXPECT_LE(c.submits, 151);  // a dab that changed nothing is no change
  EXPECT_GT(c.submits, 100);
  EXPECT_LE(c.bricks_coalesced, c.bricks_submitted);
  EXPECT_LE(c.pending_bricks_max, s.volume().brick_count());  // bounded by the volume
}

}  // namespace
}  // namespace sculpt::station
