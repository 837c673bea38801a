#pragma once
// Undo and redo per stroke (the dabs between press and release), storing only
// the bricks a stroke changed, as they were before it: a brick is copied the
// first time the stroke changes it. Undo restores those bricks' voxels bit for
// bit (the Haar bricks are lossless) and keeps their after-state for redo.
//
// Memory is capped: once the recorded bricks exceed the cap, the oldest
// strokes are forgotten (they can no longer be undone); a stroke larger than
// the cap on its own is not kept at all.

#include <cstddef>
#include <cstdint>
#include <deque>
#include <unordered_set>
#include <utility>
#include <vector>

#include <glm/vec3.hpp>

#include "sculpt/core/volume/brick.h"
#include "sculpt/core/volume/volume.h"

namespace sculpt::core {

class UndoHistory {
 public:
  static constexpr size_t kDefaultMaxBytes = size_t{256} << 20;
  explicit UndoHistory(size_t max_bytes = kDefaultMaxBytes) : max_bytes_(max_bytes) {}

  /// Starts recording a stroke (ends one still open).
  void begin_stroke();
  bool in_stroke() const { return open_; }
  /// Call before the open stroke changes brick `b` of `volume`: keeps a copy
  /// of its current content the first time per stroke.
  void before_change(const Volume& volume, glm::ivec3 b);
  /// Closes the stroke: it becomes undoable, and the redo list is cleared.
  void end_stroke();

  /// Restores the bricks of the last stroke; false when there is none.
  bool undo(Volume& volume);
  /// Re-applies the last undone stroke; false when there is none.
  bool redo(Volume& volume);
  size_t undo_depth() const { return undo_.size(); }
  size_t redo_depth() const { return redo_.size(); }
  /// Bytes held by recorded bricks.
  size_t memory_bytes() const { return bytes_; }
  /// Strokes forgotten because of the memory cap.
  int64_t dropped_strokes() const { return dropped_; }

 private:
  struct Stroke {
    std::vector<std::pair<glm::ivec3, Brick>> bricks;
    size_t bytes = 0;
  };
  // Swaps each recorded brick with the volume's current one.
  static void swap_into(Volume& volume, Stroke& stroke);
  void enforce_cap();

  size_t max_bytes_;
  bool open_ = false;
  Stroke current_;
  std::unordered_set<int64_t> current_bricks_;
  std::deque<Stroke> undo_;
  std::deque<Stroke> redo_;
  size_t bytes_ = 0;
  int64_t dropped_ = 0;
};

}  // namespace sculpt::core
