#pragma once
// The surface the window draws, meshed on a thread of its own, so that a big
// dab's re-meshing (dozens of bricks) never stalls the frame that sculpts or
// the frame that draws.
//
//   sculpting thread --submit()--> [pending bricks] --> mesher thread
//   render thread    <--take()---- [meshes ready]  <--/
//
// The mesher owns a mirror of the volume and a MixedLevelMeshCache over it.
// submit() copies the bricks the sculpting stored since the previous call
// (compared by Volume::brick_version) into a pending set and returns at
// once: it never waits for the mesher. A brick submitted again before the
// mesher took it replaces its older contents (counted as coalesced), so the
// pending set is bounded by the volume's brick count and nothing the user
// sculpted is ever lost, only intermediate states nobody would have seen.
// take() hands the render thread the brick meshes made since its previous
// call; it never waits either.
//
// A new volume is shown first at a coarse level (a sixteenth of the work)
// and refined on another thread, the refiner, on a copy of its own: the
// mesher meshes the changes made meanwhile at the coarse level too (so a
// dab on the new volume waits for a coarse re-mesh of its bricks, not for
// the whole volume's full detail) and hands them over. The refiner makes
// one pass over the volume and the changes handed over before it; the
// mesher then takes the refined meshes over, all at once, and applies and
// meshes the changes handed over during the pass itself, at full detail.
// (A refiner that caught up pass after pass chased a busy sculptor: on the
// 512^3 bust, dabs waited 280-600 ms for their full detail.) The refiner
// simplifies its meshes before it hands them over: the marched full detail
// of a whole new volume (160k triangles for the demo's head) would make
// llvmpipe's frames 40-50 ms until the simplifier, behind the sculpting and
// meshing, caught up with it. A newer volume abandons a refinement. (Measured,
// BM_MesherBigDabOnANewVolume: a 66-voxel ball on a new 256^3 sphere was
// shown 16-17 ms after its hand-over when it waited for the full detail,
// 5-7 ms meshed coarse beside the refiner.)
//
// A brick's first mesh is the march's, published at once. Another thread,
// the simplifier, at a lower priority, then simplifies each published mesh
// (core/mesh/brick_simplify.h, only its border's vertices held: it is drawn
// on its own, never welded) and publishes it again with about a tenth of
// the triangles, which are what a software renderer spends its frame on;
// the mesher never waits for it, and a mesh the mesher remade meanwhile is
// not replaced by an older one simplified. The refiner's simplification is
// the quick one (no limit on how far normals turn across a triangle, which
// costs a whole new volume's refinement twice the time: 62 against 132 ms
// on the bust); when the simplifier has nothing else to do, it simplifies
// again, from their marched meshes, the bricks where the quick one made a
// triangle that turns further than the limit.
//
// Thread safety: submit() from one thread (the one that owns the volume),
// take() from one thread (the renderer's); both may run while the mesher
// works.

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>
#include <unordered_map>
#include <vector>

#include <glm/vec3.hpp>

#include "sculpt/base/latency_histogram.h"
#include "sculpt/core/mesh/brick_mesh.h"
#include "sculpt/core/mesh/brick_simplify.h"
#include "sculpt/core/mesh/mixed_level_mesh.h"
#include "sculpt/core/volume/volume.h"

namespace sculpt::station {

/// One brick's mesh as the mesher published it.
struct BrickSurface {
  int64_t index = 0;  ///< brick order: (b.z * grid.y + b.y) * grid.x + b.x
  int level = 0;
  uint64_t version = 0;                         ///< moves on each time the brick's mesh is remade
  std::shared_ptr<const core::BrickMesh> mesh;  ///< never null
  bool simplified = false;                      ///< already simplified (refiner or simplifier)
  /// Set when `mesh` is the refiner's quick simplification: the march's
  /// mesh, for the simplifier to simplify again when it is idle.
  std::shared_ptr<const core::BrickMesh> marched;
};

/// What changed in the surface since the previous take().
struct SurfaceDelta {
  /// Everything before is gone (a new volume): the bricks listed are all.
  bool reset = false;
  std::vector<BrickSurface> bricks;
  uint64_t change = 0;  ///< the newest submitted change these meshes include
  /// The newest change whose bricks are all at full detail: a big change
  /// (a new volume) is shown at once at a coarse level, refined next.
  uint64_t full_detail_change = 0;
  /// When each change was meshed (hal::monotonic_ns()), oldest first: a
  /// delta taken late holds several, and each dab's latency ends at its
  /// own change's time, not the newest's.
  struct Readiness {
    uint64_t change = 0;
    uint64_t full_detail_change = 0;
    int64_t ready_ns = 0;
  };
  std::vector<Readiness> readiness;
};

/// The render thread's picture of the surface: the newest mesh of every
/// brick that has one, kept up to date with the mesher's deltas.
class SurfaceSnapshot {
 public:
  /// Applies a delta; returns the bricks whose mesh changed.
  int64_t apply(SurfaceDelta delta);
  const std::unordered_map<int64_t, BrickSurface>& bricks() const { return bricks_; }
  int64_t triangle_count() const;
  /// The newest submitted change the meshes include (maybe coarse).
  uint64_t change() const { return change_; }

 private:
  std::unordered_map<int64_t, BrickSurface> bricks_;  // by brick index
  uint64_t change_ = 0;
};

struct MesherCounters {
  int64_t submits = 0;           ///< changes handed over
  int64_t bricks_submitted = 0;  ///< brick copies handed over
  int64_t bricks_coalesced = 0;  ///< replaced by a newer copy before meshing
  int64_t bricks_unchanged = 0;  ///< stored again with the voxels the mesher had: not re-meshed
  int64_t updates = 0;           ///< mesh updates run
  int64_t bricks_meshed = 0;     ///< brick meshes remade
  int64_t bricks_reused = 0;     ///< given back from an earlier level of detail (zooming back)
  /// Bricks whose voxels the sculptor gave with them, not decoded again.
  int64_t bricks_given = 0;
  /// Of them, those compared with the mirror's only where the sculptor
  /// changed them (core::StoredVoxels::changed).
  int64_t bricks_compared_where_changed = 0;
  int64_t pending_bricks_max = 0;  ///< deepest the pending set got
  int64_t update_page_faults = 0;  ///< the mesher thread's, during its updates (~8 us each here)
  int64_t coarse_first = 0;        ///< new volumes shown coarse before full detail
  int64_t coarse_updates = 0;      ///< changes meshed coarse while their volume was refined
  int64_t refine_passes = 0;       ///< the refiner's updates (the first, then catching up)
  int64_t refinements = 0;         ///< refined volumes taken over
  int64_t bricks_simplified = 0;   ///< published again simplified
  int64_t bricks_polished = 0;     ///< the refiner's quick ones simplified again
  int64_t simplify_queue_max = 0;  ///< most bricks waiting to be simplified (one per brick at most)
  int64_t triangles_marched = 0;   ///< their triangles before simplifying
  int64_t triangles_kept = 0;      ///< and after
  double simplify_error_max = 0;   ///< largest estimated surface move, level-0 voxels
  LatencyHistogram update_us;      ///< time of each mesh update
  LatencyHistogram simplify_us;    ///< time of each pass of simplifying
  LatencyHistogram refine_us;      ///< time of each refiner pass
};

class SurfaceMesher {
 public:
  /// A brick's surface is simplified while it stays within this many of
  /// the brick's voxels (a fifth: 0.2 voxel at full detail, 0.8 at level 2,
  /// whose voxels span at most a pixel: LodSelector).
  static constexpr float kSimplifyError = 0.2f;
  /// How far the normals may turn across a simplified triangle
  /// (simplify_brick_mesh): beyond it, a long triangle from a crease into
  /// the smooth clay around shows as a streak (stars around the played
  /// demo's eyes and mouth). The demo at 37 degrees: 37k triangles drawn
  /// against 31k with no limit, pixels more than 8 levels off the marched
  /// picture 0.20% against 0.61% (1280x800); at 26 degrees 49k and 0.16%.
  static constexpr float kMaxNormalTurnDeg = 37.0f;
  /// Along a simplified edge longer than this (level-0 voxels, at level 0),
  /// the normals may turn only kMaxNormalTurnDeg times this over its length:
  /// a long triangle from a crease's rim into the flat clay around, its
  /// normals well within the limit, spreads the rim's turn over its length,
  /// a dark wedge beside an eye socket. The played demo project at 640x400
  /// (pixels more than 8 levels off the marched picture; triangles): 0.075%
  /// and 36.8k with no such rule, 0.054% and 39.7k at 4 voxels (a faint
  /// trace left on the nose), 0.034% and 42.5k at 3; the bust 86k -> 96k
  /// triangles at 4.
  static constexpr float kFullTurnLengthVox = 4.0f;
  /// How far a vertex the simplifier removed may turn from the normal the
  /// triangle made over it interpolates: where the clay turns one way and
  /// back between a triangle's corners (a concave fillet), neither rule
  /// above sees the turn dropped, a light blob (the bust's eyebrow ends, a
  /// V on the demo's nose). 1280x800, pixels more than 8 levels off the
  /// marched picture, and triangles: the played demo 0.079% -> 0.038%,
  /// 39.7k -> 42.2k; the bust 0.026% -> 0.011%, 95.9k -> 101.7k (its
  /// frames about 0.7 ms longer). At 10 and 12 degrees traces stay. The
  /// refiner's quick pass (TurnLimit::kCount) does not look at removed
  /// vertices: the demo project opened shows 0.035%. At full detail only:
  /// a coarser level's voxels span at most a pixel (LodSelector), and its
  /// density normals are some 4 degrees off themselves, so the rule held
  /// that noise (the demo zoomed out, window_test.cpp: 21.3k -> 33.1k
  /// triangles).
  static constexpr float kMaxRemovedTurnDeg = 8.0f;
  /// The limit for a brick at `level` (its voxels 2^level level-0 voxels).
  static core::NormalTurnLimit turn_limit(int level) {
    return {kMaxNormalTurnDeg, kFullTurnLengthVox * static_cast<float>(1 << level),
            level == 0 ? kMaxRemovedTurnDeg : 180.0f};
  }
  /// The refiner's quick pass: turn_limit(level)'s places only counted
  /// (core::TurnLimit::kCount), the bricks with any polished later.
  static core::NormalTurnLimit quick_turn_limit(int level) {
    core::NormalTurnLimit turn = turn_limit(level);
    turn.action = core::TurnLimit::kCount;
    return turn;
  }

  /// `threads` mesh the changed bricks of one update in parallel (0: all
  /// cores); the meshes do not depend on it. `simplify_error`: in voxels of
  /// each brick's level; 0 publishes the march's meshes only.
  /// `warm_heap_bytes`: the mesher and the refiner threads each touch that
  /// much of their heap when they start (memory_reuse.h), so that the first
  /// big dab's meshes do not fault page by page (the window's first
  /// 66-voxel ball: 3600 faults, 34 ms against 9 for the next ball), nor the
  /// new block's refinement beside it (4700 faults in the demo's first half
  /// second).
  explicit SurfaceMesher(int threads = 0, float simplify_error = kSimplifyError,
                         size_t warm_heap_bytes = 0);
  ~SurfaceMesher();
  SurfaceMesher(const SurfaceMesher&) = delete;
  SurfaceMesher& operator=(const SurfaceMesher&) = delete;

  /// Hands over what changed in `volume` since the previous call (all of it
  /// when `generation` differs: a replaced volume) and the level to draw
  /// each brick at (brick order). Returns the change's number (increasing);
  /// returns the previous number and does nothing when neither bricks nor
  /// levels changed. `queued_ns`, when given, is set to when a change was
  /// queued (hal::monotonic_ns(), before the mesher is woken) and left alone
  /// when none was: waking the mesher can give it the core at once and keep
  /// the caller off one for milliseconds, which a caller timing its
  /// hand-over after the return would count as handing over. `stored`: the
  /// voxels of bricks as the sculptor stored them (Sculptor::
  /// take_stored_voxels()), taken instead of decoding those bricks again.
  uint64_t submit(const core::Volume& volume, uint64_t generation, const std::vector<int>& levels,
                  int64_t* queued_ns = nullptr, core::StoredVoxelsByBrick stored = {});

  /// The meshes made since the previous call; nothing when none.
  std::optional<SurfaceDelta> take();

  /// Waits until the mesher and refiner threads have touched the heap they were given
  /// (warm_heap_bytes; at once when none): the window starts its devices
  /// after it, so a first dab never waits for it.
  void wait_until_warm();

  /// Waits until every submitted change is meshed, simplified and ready to
  /// take (tests, a screenshot of a given frame, the end of a run).
  void wait_until_meshed();
  /// Whether wait_until_meshed() would return at once: every change handed
  /// over meshed, refined and simplified.
  bool meshed() const;

  MesherCounters counters() const;

  /// Tests: while held, a refinement makes no pass, so the coarse meshes of
  /// a new volume and of the changes after it can be seen to come first.
  /// wait_until_meshed() waits for the refinement too: release it first.
  void hold_refinement(bool hold);
  /// Tests: while held, the mesher does not take a finished refinement
  /// over, so the changes made after its one pass can be seen to wait for
  /// the take-over, not for another pass. wait_until_meshed() waits for the
  /// take-over too: release it first.
  void hold_take_over(bool hold);

 private:
  struct Pending {
    std::unique_ptr<core::Volume> reset;              // a whole new volume
    std::unordered_map<int64_t, core::Brick> bricks;  // by brick index
    core::StoredVoxelsByBrick stored;                 // some of their voxels
    std::vector<int> levels;
    uint64_t change = 0;
  };
  // A brick's mesh in the refiner's cache simplified (quickly), the marched
  // one when a triangle the simplifier made turns too far (to simplify
  // again with the limit), and the cache's mesh version they are of.
  struct RefinedBrick {
    std::shared_ptr<const core::BrickMesh> simplified, marched;
    uint64_t version = 0;
  };
  // A new volume's full-detail meshes, made on the refiner's copy.
  struct Refinement {
    uint64_t epoch = 0;                    // which volume: a newer one abandons it
    std::unique_ptr<core::Volume> volume;  // null while the refiner works on it
    std::unique_ptr<core::MixedLevelMeshCache> cache;
    std::unordered_map<int64_t, core::Brick> bricks;  // handed over, not applied yet
    std::vector<int> levels;                          // the full-detail levels
    uint64_t change = 0;                              // the newest change handed over
    uint64_t refined_change = 0;                      // the change its one pass meshed (0: not yet)
    std::vector<RefinedBrick> meshes;                 // per brick
    bool ready() const { return volume && refined_change != 0; }
  };
  void run();
  void refine();
  // meshed(), mutex_ held.
  bool all_meshed_locked() const;
  // Touches `bytes` of this thread's heap, then counts it warm.
  void warm_this_thread(size_t bytes);
  /// Simplifies the bricks the refinement's cache remade (in parallel,
  /// quickly), keeping copies of the marched meshes that need the limit.
  void simplify_refined(const core::MixedLevelMeshCache& cache, std::vector<RefinedBrick>& refined);
  void simplify();
  // One brick's mesh simplified within simplify_error_ voxels of its level,
  // and what it counts for (count_simplified(), mutex_ held).
  struct Simplified {
    std::shared_ptr<const core::BrickMesh> mesh;
    int64_t marched = 0, kept = 0;  // triangles before and after
    float error = 0.0f;
    int64_t turning = 0;  // places left turning further than turn_limit() allows
  };
  // `quick`: the places turning further than turn_limit() allows only
  // counted, not avoided (core::TurnLimit::kCount).
  Simplified simplify_brick(const core::BrickMesh& mesh, int level, bool quick = false) const;
  void count_simplified(const Simplified& s);
  /// Stamps the bricks' versions, queues them to simplify and hands them
  /// to take().
  void publish(SurfaceDelta delta);
  /// Merges into the meshes not taken yet (mutex_ held).
  void merge_ready(SurfaceDelta delta);

  const int threads_;
  const float simplify_error_;
  // Sculpting side only.
  uint64_t generation_ = ~uint64_t{0};
  std::vector<uint64_t> sent_versions_;
  uint64_t sent_stores_ = 0;  // volume.stores() as of the previous submit
  std::vector<int> sent_levels_;
  uint64_t change_ = 0;

  mutable std::mutex mutex_;
  std::condition_variable wake_;           // the mesher: work or stop
  std::condition_variable meshed_;         // wait_until_meshed()
  std::condition_variable simplify_wake_;  // the simplifier: work or stop
  std::condition_variable refine_wake_;    // the refiner: work or stop
  Pending pending_;
  bool has_pending_ = false;
  bool busy_ = false;
  int threads_warm_ =
      0;  // of the mesher and the refiner, those whose heap is touched (meshed_ tells)
  std::unique_ptr<Refinement> refinement_;  // the newest volume's, until taken over
  uint64_t refine_epochs_ = 0;
  // The epoch of the refinement under way (0: none), read by the refiner's
  // pass between bricks: a pass whose volume was replaced stops.
  std::atomic<uint64_t> current_epoch_{0};
  bool hold_refinement_ = false;
  bool hold_take_over_ = false;
  // Meshes waiting for the simplifier, oldest first, one per brick (a newer
  // mesh of a brick replaces the one waiting, in its place).
  class SimplifyQueue {
   public:
    void put(BrickSurface job);
    void drop(int64_t index);
    std::optional<BrickSurface> take();  // the oldest, if any
    bool empty() const { return jobs_.empty(); }
    size_t size() const { return jobs_.size(); }
    void clear();

   private:
    std::deque<int64_t> order_;  // may name bricks dropped since: take() skips them
    std::unordered_map<int64_t, BrickSurface> jobs_;
  };
  SimplifyQueue fresh_;   // published meshes as marched
  SimplifyQueue polish_;  // the refiner's quick ones, done when no fresh one waits
  bool simplifying_ = false;
  std::unordered_map<int64_t, uint64_t> newest_version_;  // per brick, as published
  uint64_t versions_ = 0;                                 // handed out, across volumes
  uint64_t last_change_ = 0, last_full_detail_change_ = 0;
  bool stop_ = false;
  std::optional<SurfaceDelta> ready_;
  MesherCounters counters_;
  std::thread thread_;
  std::thread simplifier_;
  std::thread refiner_;
};

}  // namespace sculpt::station
