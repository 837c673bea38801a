#pragma once
// How a patch crosses from the sculpting thread to the haptic tick (DESIGN.md
// §5a) without either side waiting: three snapshots, one being written, one
// being read, and one ready in between (a triple buffer). publish() swaps the
// written one with the ready one, acquire() swaps the read one with the ready
// one when a newer one is there; each is one atomic exchange. Neither side
// ever blocks, the tick never allocates (the snapshots are sized up front),
// and the tick always reads a whole snapshot from one publish.
//
// Thread safety: one writer thread (back(), publish()) and one reader thread
// (acquire(), front()).

#include <array>
#include <atomic>
#include <cstdint>

#include "sculpt/core/haptics/patch_snapshot.h"

namespace sculpt::core {

class PatchExchange {
 public:
  /// Snapshots with room for edge^3 values each.
  explicit PatchExchange(int edge);

  /// Writer: the snapshot to fill next (its previous contents are stale).
  PatchSnapshot& back() { return buffers_[back_]; }
  /// Writer: makes back() the newest snapshot; back() is then another one.
  void publish();

  /// Reader: the newest published snapshot (empty before the first publish).
  const PatchSnapshot& acquire();
  /// Reader: what the last acquire() returned.
  const PatchSnapshot& front() const { return buffers_[front_]; }

 private:
  static constexpr uint32_t kFresh = 4;  // the ready slot holds an unread publish
  std::array<PatchSnapshot, 3> buffers_;
  std::atomic<uint32_t> ready_{1};
  uint32_t back_ = 0;   // writer's own
  uint32_t front_ = 2;  // reader's own
};

/// Copies a patch into a snapshot of the exchange, reusing its memory.
void copy_snapshot(const PatchSnapshot& from, PatchSnapshot& to);

}  // namespace sculpt::core
