#include "sculpt/station/view/surface_mesher.h"

#include <algorithm>
#include <utility>

#include "sculpt/base/memory_reuse.h"
#include "sculpt/base/thread_priority.h"
#include "sculpt/base/thread_times.h"
#include "sculpt/core/mesh/brick_simplify.h"
#include "sculpt/core/mesh/mixed_level_mesh.h"
#include "sculpt/core/util/parallel_for.h"
#include "sculpt/hal/types/clock.h"

namespace sculpt::station {
namespace {

// The level a new volume is first shown at.
constexpr int kCoarseLevel = 2;
// Simplifying is the least urgent work of the window: it yields the cores
// to sculpting, meshing and drawing (thread_priority.h; failing to is
// harmless).
constexpr int kSimplifierNice = 10;

}  // namespace

SurfaceMesher::SurfaceMesher(int threads, float simplify_error, size_t warm_heap_bytes)
    : threads_(threads),
      simplify_error_(simplify_error),
      thread_([this, warm_heap_bytes] {
        name_this_thread("mesher");
        warm_this_thread(warm_heap_bytes);
        run();
      }),
      simplifier_([this] {
        name_this_thread("simplifier");
        const int self[] = {this_thread_id()};
        make_threads_nicer(self, kSimplifierNice);
        simplify();
      }),
      refiner_([this, warm_heap_bytes] {
        name_this_thread("refiner");
        warm_this_thread(warm_heap_bytes);
        refine();
      }) {}

SurfaceMesher::~SurfaceMesher() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  simplify_wake_.notify_all();
  refine_wake_.notify_all();
  thread_.join();
  simplifier_.join();
  refiner_.join();
}

uint64_t SurfaceMesher::submit(const core::Volume& volume, uint64_t generation,
                               const std::vector<int>& levels, int64_t* queued_ns,
                               core::StoredVoxelsByBrick stored) {
  const bool reset = generation != generation_;
  // Nothing stored since the previous call (most of the sculpting thread's
  // thousand calls a second): no brick to look at.
  if (!reset && volume.stores() == sent_stores_ && levels == sent_levels_) return change_;
  sent_stores_ = volume.stores();
  const glm::ivec3 grid = volume.brick_grid();
  struct Changed {
    int64_t index;
    const core::Brick* brick;
    uint64_t version;
    uint64_t sent;  // the version sent before: the mirror's voxels, as they will be
  };
  std::vector<Changed> changed;
  if (reset) {
    generation_ = generation;
    sent_versions_.assign(static_cast<size_t>(volume.brick_count()), 0);
  }
  for (int64_t i = 0; i < volume.brick_count(); ++i) {
    const glm::ivec3 b = core::grid_position(i, grid);
    uint64_t& sent = sent_versions_[static_cast<size_t>(i)];
    if (!reset && sent == volume.brick_version(b)) continue;
    const uint64_t before = std::exchange(sent, volume.brick_version(b));
    if (!reset) changed.push_back({i, &volume.brick(b), sent, before});
  }
  if (!reset && changed.empty() && levels == sent_levels_) return change_;
  sent_levels_ = levels;
  // Copies made before taking the lock: the mesher is never held up by them.
  std::unique_ptr<core::Volume> whole;
  if (reset) whole = std::make_unique<core::Volume>(volume);
  std::vector<std::pair<int64_t, core::Brick>> copies;
  copies.reserve(changed.size());
  for (const Changed& c : changed)
    copies.emplace_back(c.index, *c.brick);
  {
    std::lock_guard lock(mutex_);
    Pending& p = pending_;
    if (whole) {
      p.reset = std::move(whole);
      p.bricks.clear();  // the copy holds them
      p.stored.clear();
    }
    for (size_t k = 0; k < copies.size(); ++k) {
      auto& [i, brick] = copies[k];
      const bool added = p.bricks.insert_or_assign(i, std::move(brick)).second;
      if (!added) ++counters_.bricks_coalesced;
      // The stored voxels of this very version, or none (older ones go).
      // What changed in them holds against the mirror's voxels when it
      // holds against the version sent before, and that one is what the
      // mirror holds (or a waiting one whose own changes do).
      auto s = stored.find(i);
      if (s == stored.end() || s->second.version != changed[k].version) {
        p.stored.erase(i);
        continue;
      }
      core::StoredVoxels& now = s->second;
      if (now.changed_from != changed[k].sent) now.changed_from.reset();
      if (!added) {
        const auto waiting = p.stored.find(i);
        if (waiting == p.stored.end()) {
          now.changed_from.reset();
        } else {
          core::follow(waiting->second, now);
        }
      }
      p.stored.insert_or_assign(i, std::move(now));
    }
    p.levels = levels;
    p.change = ++change_;
    has_pending_ = true;
    ++counters_.submits;
    counters_.bricks_submitted += static_cast<int64_t>(copies.size());
    counters_.pending_bricks_max =
        std::max(counters_.pending_bricks_max, static_cast<int64_t>(p.bricks.size()));
  }
  if (queued_ns != nullptr) *queued_ns = hal::monotonic_ns();
  wake_.notify_one();
  return change_;
}

int64_t SurfaceSnapshot::apply(SurfaceDelta delta) {
  if (delta.reset) bricks_.clear();
  change_ = std::max(change_, delta.change);
  int64_t changed = 0;
  for (BrickSurface& b : delta.bricks) {
    ++changed;
    if (b.mesh->empty()) {
      bricks_.erase(b.index);
    } else {
      bricks_.insert_or_assign(b.index, std::move(b));
    }
  }
  return changed;
}

int64_t SurfaceSnapshot::triangle_count() const {
  int64_t n = 0;
  for (const auto& [index, b] : bricks_)
    n += static_cast<int64_t>(b.mesh->mesh.triangles.size());
  return n;
}

std::optional<SurfaceDelta> SurfaceMesher::take() {
  std::lock_guard lock(mutex_);
  return std::exchange(ready_, std::nullopt);
}

void SurfaceMesher::warm_this_thread(size_t bytes) {
  if (bytes > 0) warm_this_threads_heap(bytes);
  {
    std::lock_guard lock(mutex_);
    ++threads_warm_;
  }
  meshed_.notify_all();
}

void SurfaceMesher::wait_until_warm() {
  std::unique_lock lock(mutex_);
  meshed_.wait(lock, [&] { return threads_warm_ == 2; });  // the mesher and the refiner
}

bool SurfaceMesher::all_meshed_locked() const {
  return !has_pending_ && !busy_ && !refinement_ && fresh_.empty() && polish_.empty() &&
         !simplifying_;
}

void SurfaceMesher::wait_until_meshed() {
  std::unique_lock lock(mutex_);
  meshed_.wait(lock, [&] { return all_meshed_locked(); });
}

bool SurfaceMesher::meshed() const {
  std::lock_guard lock(mutex_);
  return all_meshed_locked();
}

void SurfaceMesher::hold_take_over(bool hold) {
  {
    std::lock_guard lock(mutex_);
    hold_take_over_ = hold;
  }
  wake_.notify_all();
}

void SurfaceMesher::hold_refinement(bool hold) {
  {
    std::lock_guard lock(mutex_);
    hold_refinement_ = hold;
  }
  refine_wake_.notify_all();
}

MesherCounters SurfaceMesher::counters() const {
  std::lock_guard lock(mutex_);
  return counters_;
}

void SurfaceMesher::publish(SurfaceDelta delta) {
  std::lock_guard lock(mutex_);
  if (delta.reset) {
    newest_version_.clear();
    fresh_.clear();
    polish_.clear();
  }
  for (BrickSurface& b : delta.bricks) {
    // Versions count across volumes (a fresh cache restarts at 1): a
    // renderer's stamp never matches a mesh of another volume.
    b.version = ++versions_;
    newest_version_[b.index] = b.version;
    if (simplify_error_ > 0 && !b.mesh->empty() && !b.simplified) {
      fresh_.put(b);
    } else {
      fresh_.drop(b.index);
    }
    polish_.drop(b.index);  // for an older mesh
    if (b.marched) {
      BrickSurface again = b;
      again.mesh = std::move(again.marched);
      again.simplified = false;
      b.marched = nullptr;  // the renderer draws `mesh` alone
      polish_.put(std::move(again));
    }
  }
  counters_.simplify_queue_max =
      std::max(counters_.simplify_queue_max, static_cast<int64_t>(fresh_.size()));
  last_change_ = delta.change;
  last_full_detail_change_ = std::max(last_full_detail_change_, delta.full_detail_change);
  merge_ready(std::move(delta));
  simplify_wake_.notify_one();
}

void SurfaceMesher::merge_ready(SurfaceDelta delta) {
  if (ready_ && delta.reset) {
    // The meshes go, the times of the changes they showed stay.
    delta.readiness.insert(delta.readiness.begin(), ready_->readiness.begin(),
                           ready_->readiness.end());
  }
  if (!ready_ || delta.reset) {
    ready_ = std::move(delta);
    return;
  }
  // Not taken yet: a newer mesh of a brick replaces the older one.
  SurfaceDelta& merged = *ready_;
  std::unordered_map<int64_t, size_t> at;
  for (size_t k = 0; k < merged.bricks.size(); ++k)
    at[merged.bricks[k].index] = k;
  for (BrickSurface& b : delta.bricks) {
    if (auto it = at.find(b.index); it != at.end()) {
      merged.bricks[it->second] = std::move(b);
    } else {
      merged.bricks.push_back(std::move(b));
    }
  }
  merged.change = delta.change;
  merged.full_detail_change = std::max(merged.full_detail_change, delta.full_detail_change);
  merged.readiness.insert(merged.readiness.end(), delta.readiness.begin(), delta.readiness.end());
}

void SurfaceMesher::run() {
  std::unique_ptr<core::Volume> mirror;
  const core::MarchingCubesOptions options{.threads = threads_};
  auto cache = std::make_unique<core::MixedLevelMeshCache>(options);
  std::vector<uint64_t> published;  // the cache's mesh version per brick as last published
  uint64_t full_detail_change = 0;
  // The mirror's volume is being refined: its changes are meshed coarse.
  bool refining = false;
  // Hands take() the cache's meshes remade since last published (all of
  // them, as the whole surface, when `all`).
  auto publish_cache = [&](uint64_t change, bool full_detail, bool all,
                           const Refinement* refined = nullptr) {
    const glm::ivec3 grid = mirror->brick_grid();
    SurfaceDelta delta;
    delta.reset = all;
    delta.change = change;
    if (full_detail) full_detail_change = change;
    delta.full_detail_change = full_detail_change;
    for (int64_t i = 0; i < mirror->brick_count(); ++i) {
      const glm::ivec3 b = core::grid_position(i, grid);
      const uint64_t version = cache->brick_mesh_version(b);
      if (!all && published[static_cast<size_t>(i)] == version) continue;
      published[static_cast<size_t>(i)] = version;
      std::shared_ptr<const core::BrickMesh> mesh = cache->shared_brick_mesh(b);
      if (all && mesh->empty()) continue;
      if (refined != nullptr && refined->meshes[static_cast<size_t>(i)].simplified) {
        const RefinedBrick& r = refined->meshes[static_cast<size_t>(i)];
        delta.bricks.push_back({i, cache->brick_level(b), 0, r.simplified, true, r.marched});
        continue;
      }
      delta.bricks.push_back({i, cache->brick_level(b), 0, std::move(mesh), false, {}});
    }
    delta.readiness.push_back({delta.change, delta.full_detail_change, hal::monotonic_ns()});
    publish(std::move(delta));
  };
  for (;;) {
    Pending work;
    std::unique_ptr<Refinement> refined;
    {
      std::unique_lock lock(mutex_);
      auto take_over = [&] { return refinement_ && refinement_->ready() && !hold_take_over_; };
      wake_.wait(lock, [&] { return stop_ || has_pending_ || take_over(); });
      if (stop_) return;
      if (take_over()) {
        refined = std::move(refinement_);
        refinement_.reset();
      } else {
        work = std::move(pending_);
        pending_ = Pending{};
        has_pending_ = false;
      }
      busy_ = true;
    }
    if (refined) {
      // The refiner's pass is done: its volume and meshes take over, and
      // replace every coarse mesh. The changes handed over during the pass
      // are applied and meshed here, at full detail, as any change is: a
      // refiner that caught up pass after pass chased a busy sculptor (on
      // the 512^3 bust, dabs waited 280-600 ms for their full detail).
      mirror = std::move(refined->volume);
      cache = std::move(refined->cache);
      const glm::ivec3 grid = mirror->brick_grid();
      for (auto& [i, brick] : refined->bricks)
        mirror->replace_brick(core::grid_position(i, grid), std::move(brick));
      const core::MeshUpdate update = cache->update(*mirror, refined->levels);
      for (int64_t i = 0; i < mirror->brick_count(); ++i) {
        RefinedBrick& r = refined->meshes[static_cast<size_t>(i)];
        if (r.version != cache->brick_mesh_version(core::grid_position(i, grid)))
          r = {};  // remade since: not simplified
      }
      published.assign(static_cast<size_t>(mirror->brick_count()), 0);
      publish_cache(refined->change, true, true, refined.get());
      refining = false;
      {
        std::lock_guard lock(mutex_);
        busy_ = false;
        ++counters_.refinements;
        counters_.bricks_meshed += update.bricks_meshed;
      }
      meshed_.notify_all();
      continue;
    }
    const int64_t start = hal::monotonic_ns();
    const bool reset = work.reset != nullptr;
    if (reset) {
      mirror = std::move(work.reset);
      cache = std::make_unique<core::MixedLevelMeshCache>(options);
      published.assign(static_cast<size_t>(mirror->brick_count()), 0);
    }
    const glm::ivec3 grid = mirror->brick_grid();
    // A brick stored again with the voxels it had is not re-meshed: a ball
    // brush's preview puts its whole path back and brushes it again, and
    // only the bricks near the path's new end come out different.
    int64_t unchanged = 0;
    if (!reset)
      unchanged = static_cast<int64_t>(std::erase_if(work.bricks, [&](const auto& entry) {
        return mirror->brick(core::grid_position(entry.first, grid))
            .holds_same_voxels(entry.second);
      }));
    // A refinement under way is handed the change too: copies, as the
    // mirror takes the bricks.
    std::unordered_map<int64_t, core::Brick> handed;
    if (refining && !reset) handed = work.bricks;
    // The sculptor's voxels of the bricks replaced, as of the mirror's
    // versions of them (a brick found unchanged keeps its mesh: none); what
    // changed in them holds against the mirror's voxels before.
    for (auto it = work.stored.begin(); it != work.stored.end();) {
      if (!work.bricks.contains(it->first)) {
        it = work.stored.erase(it);
        continue;
      }
      const glm::ivec3 b = core::grid_position(it->first, grid);
      if (it->second.changed_from) it->second.changed_from = mirror->brick_version(b);
      it->second.version = mirror->brick_version(b) + 1;  // replace_brick() moves it on by one
      ++it;
    }
    for (auto& [i, brick] : work.bricks)
      mirror->replace_brick(core::grid_position(i, grid), std::move(brick));
    // A new volume is shown first at a coarse level (a sixteenth of the
    // work at level 2: 7 ms against 92 for the demo's head) and refined on
    // the refiner's copy, so the first dabs on it wait for a coarse re-mesh
    // of their bricks, not for the full detail. (A big dab's bricks are not
    // shown coarse first: their unchanged neighbours must re-stitch against
    // the coarse level at their own, and that pass costs more than the full
    // one: 14.6-31 ms against 3.7-10.1 for the demo's head balls, the 208
    // bricks around the first one's 92 taking most of it; docs/performance.md,
    // twenty-ninth session.)
    const int coarse = std::min(kCoarseLevel, mirror->levels());
    if (reset) {
      refining =
          std::any_of(work.levels.begin(), work.levels.end(), [&](int l) { return l < coarse; });
      std::unique_ptr<Refinement> abandoned;
      {
        std::lock_guard lock(mutex_);
        abandoned = std::move(refinement_);
        refinement_.reset();
        if (refining) {
          refinement_ = std::make_unique<Refinement>();
          refinement_->epoch = ++refine_epochs_;
          refinement_->levels = work.levels;
          refinement_->change = work.change;
        }
        current_epoch_.store(refining ? refinement_->epoch : 0, std::memory_order_relaxed);
      }
    } else if (refining) {
      {
        std::lock_guard lock(mutex_);
        for (auto& [i, brick] : handed)
          refinement_->bricks.insert_or_assign(i, std::move(brick));
        refinement_->levels = work.levels;
        refinement_->change = work.change;
      }
      refine_wake_.notify_one();
    }
    std::vector<int> levels = work.levels;
    if (refining)
      for (int& l : levels)
        l = std::max(l, coarse);
    const int64_t faults_before = this_threads_page_faults();
    const core::MeshUpdate update = cache->update(*mirror, levels, &work.stored);
    publish_cache(work.change, !refining, reset);
    if (reset && refining) {
      // Copied once the coarse meshes are out (they come first) and outside
      // the lock; the refiner starts when the copy is there.
      auto copy = std::make_unique<core::Volume>(*mirror);
      auto refined_cache = std::make_unique<core::MixedLevelMeshCache>(options);
      {
        std::lock_guard lock(mutex_);
        refinement_->volume = std::move(copy);
        refinement_->cache = std::move(refined_cache);
        refinement_->meshes.assign(static_cast<size_t>(mirror->brick_count()), {});
      }
      refine_wake_.notify_one();
    }
    const int64_t faults = this_threads_page_faults() - faults_before;
    const int64_t end = hal::monotonic_ns();
    {
      std::lock_guard lock(mutex_);
      busy_ = false;
      ++counters_.updates;
      counters_.bricks_meshed += update.bricks_meshed;
      counters_.bricks_reused += update.bricks_reused;
      counters_.bricks_given += update.bricks_given;
      counters_.bricks_compared_where_changed += update.bricks_compared_where_changed;
      counters_.bricks_unchanged += unchanged;
      counters_.coarse_first += reset && refining ? 1 : 0;
      counters_.coarse_updates += !reset && refining ? 1 : 0;
      counters_.update_page_faults += faults;
      counters_.update_us.add(static_cast<double>(end - start) * 1e-3);
    }
    meshed_.notify_all();
  }
}

void SurfaceMesher::refine() {
  std::unique_lock lock(mutex_);
  for (;;) {
    refine_wake_.wait(lock, [&] {
      return stop_ || (!hold_refinement_ && refinement_ && refinement_->volume &&
                       refinement_->refined_change == 0);
    });
    if (stop_) return;
    // The volume and its cache are the refiner's alone during a pass.
    Refinement& r = *refinement_;
    const uint64_t epoch = r.epoch;
    const uint64_t change = r.change;
    std::unique_ptr<core::Volume> volume = std::move(r.volume);
    std::unique_ptr<core::MixedLevelMeshCache> cache = std::move(r.cache);
    std::unordered_map<int64_t, core::Brick> bricks = std::move(r.bricks);
    r.bricks.clear();
    std::vector<RefinedBrick> meshes = std::move(r.meshes);
    const std::vector<int> levels = r.levels;
    lock.unlock();
    const int64_t start = hal::monotonic_ns();
    const glm::ivec3 grid = volume->brick_grid();
    for (auto& [i, brick] : bricks)
      volume->replace_brick(core::grid_position(i, grid), std::move(brick));
    // A newer volume ends the pass between bricks (its result is dropped).
    auto replaced = [this, epoch] {
      return current_epoch_.load(std::memory_order_relaxed) != epoch;
    };
    cache->set_cancel(replaced);
    (void)cache->update(*volume, levels);
    cache->set_cancel(nullptr);
    if (simplify_error_ > 0 && !replaced()) simplify_refined(*cache, meshes);
    const int64_t end = hal::monotonic_ns();
    lock.lock();
    ++counters_.refine_passes;
    counters_.refine_us.add(static_cast<double>(end - start) * 1e-3);
    if (!refinement_ || refinement_->epoch != epoch) {
      // A newer volume came: this one is dropped (outside the lock).
      lock.unlock();
      volume.reset();
      cache.reset();
      lock.lock();
      continue;
    }
    refinement_->volume = std::move(volume);
    refinement_->cache = std::move(cache);
    refinement_->meshes = std::move(meshes);
    refinement_->refined_change = change;
    wake_.notify_one();
  }
}

void SurfaceMesher::simplify_refined(const core::MixedLevelMeshCache& cache,
                                     std::vector<RefinedBrick>& refined) {
  const glm::ivec3 grid = cache.brick_grid();
  std::vector<int64_t> remade;
  for (int64_t i = 0; i < static_cast<int64_t>(refined.size()); ++i) {
    const glm::ivec3 b = core::grid_position(i, grid);
    RefinedBrick& r = refined[static_cast<size_t>(i)];
    if (r.version == cache.brick_mesh_version(b)) continue;
    r = {nullptr, nullptr, cache.brick_mesh_version(b)};
    if (!cache.brick_mesh(b).empty()) remade.push_back(i);
  }
  std::vector<Simplified> done(remade.size());
  core::parallel_for(
      static_cast<int64_t>(remade.size()),
      [&](int64_t k) {
        const int64_t i = remade[static_cast<size_t>(k)];
        const glm::ivec3 b = core::grid_position(i, grid);
        const Simplified& s = done[static_cast<size_t>(k)] =
            simplify_brick(cache.brick_mesh(b), cache.brick_level(b), /*quick=*/true);
        RefinedBrick& r = refined[static_cast<size_t>(i)];
        r.simplified = s.mesh;
        if (s.turning > 0) r.marched = cache.shared_brick_mesh(b);
      },
      threads_);
  std::lock_guard lock(mutex_);
  for (const Simplified& d : done)
    count_simplified(d);
}

SurfaceMesher::Simplified SurfaceMesher::simplify_brick(const core::BrickMesh& mesh, int level,
                                                        bool quick) const {
  // Drawn brick by brick, never welded: only the border's vertices stay.
  const core::NormalTurnLimit turn = quick ? quick_turn_limit(level) : turn_limit(level);
  core::SimplifiedBrick s = core::simplify_brick_mesh(
      mesh, simplify_error_ * static_cast<float>(1 << level), core::BorderHold::kVertices, turn);
  Simplified out;
  out.marched = static_cast<int64_t>(mesh.mesh.triangles.size());
  out.kept = static_cast<int64_t>(s.brick.mesh.triangles.size());
  out.error = s.error;
  out.turning = s.turning;
  out.mesh = std::make_shared<const core::BrickMesh>(std::move(s.brick));
  return out;
}

void SurfaceMesher::count_simplified(const Simplified& s) {
  ++counters_.bricks_simplified;
  counters_.triangles_marched += s.marched;
  counters_.triangles_kept += s.kept;
  counters_.simplify_error_max =
      std::max(counters_.simplify_error_max, static_cast<double>(s.error));
}

void SurfaceMesher::SimplifyQueue::put(BrickSurface job) {
  const int64_t index = job.index;
  if (!jobs_.contains(index)) order_.push_back(index);
  jobs_[index] = std::move(job);
}

void SurfaceMesher::SimplifyQueue::drop(int64_t index) {
  jobs_.erase(index);
  if (jobs_.empty()) order_.clear();
}

std::optional<BrickSurface> SurfaceMesher::SimplifyQueue::take() {
  while (!order_.empty()) {
    const int64_t index = order_.front();
    order_.pop_front();
    const auto it = jobs_.find(index);
    if (it == jobs_.end()) continue;  // dropped since
    BrickSurface job = std::move(it->second);
    jobs_.erase(it);
    return job;
  }
  return std::nullopt;
}

void SurfaceMesher::SimplifyQueue::clear() {
  order_.clear();
  jobs_.clear();
}

void SurfaceMesher::simplify() {
  std::unique_lock lock(mutex_);
  for (;;) {
    if (fresh_.empty() && polish_.empty()) meshed_.notify_all();
    simplify_wake_.wait(lock, [&] { return stop_ || !fresh_.empty() || !polish_.empty(); });
    if (stop_) return;
    // A fresh mesh first; the refiner's quick ones when there is none.
    const bool polish = fresh_.empty();
    BrickSurface job = *(polish ? polish_ : fresh_).take();
    const int64_t index = job.index;
    if (polish) ++counters_.bricks_polished;
    simplifying_ = true;
    lock.unlock();
    const int64_t start = hal::monotonic_ns();
    const Simplified simplified = simplify_brick(*job.mesh, job.level);
    job.mesh = simplified.mesh;
    job.simplified = true;
    const int64_t end = hal::monotonic_ns();
    lock.lock();
    simplifying_ = false;
    count_simplified(simplified);
    counters_.simplify_us.add(static_cast<double>(end - start) * 1e-3);
    // The mesher may have remade the brick meanwhile: its newer mesh stays.
    if (newest_version_[index] != job.version) continue;
    job.version = ++versions_;
    newest_version_[index] = job.version;
    // Changes already shown: no dab waits on this delta, which says when
    // no change was ready.
    SurfaceDelta delta;
    delta.change = ready_ ? ready_->change : last_change_;
    delta.full_detail_change = ready_ ? ready_->full_detail_change : last_full_detail_change_;
    delta.bricks.push_back(std::move(job));
    merge_ready(std::move(delta));
  }
}

}  // namespace sculpt::station
